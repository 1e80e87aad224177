// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// A dynamic tool's reaction to the nodes ThinTool moves off it. The moves are positional, as if
// the tool were infinitely heavy; the tool's share is the node's change of momentum, capped at what
// a perfectly inelastic collision of the node with the tool would exchange: the reduced mass of the
// node and the tool's effective mass at the point (rotation included, as the normal row of a
// sequential-impulse contact solver such as Box2D's has it) times their closing speed. Without the
// cap a tool lighter at that point than the node (a needle about its own axis, a light blade) is
// sent back faster than it came, and the next step's larger moves send it back faster still.

#include "DynamicBody.h"
#include "tool/ToolModel.h"

#include <thintool/core/Math.h>

#include <LinearMath/btVector3.h>

class btRigidBody;

namespace thintool::detail {

/// Applies to tool the reaction of a node of inverse mass inverseNodeMass (1/kg; 0 for a node that
/// cannot give way) that moved at nodeVelocity (m/s, world) before ThinTool moved it by
/// displacement (m) to nodePosition in a step of inverseStep (1/s): the node's change of momentum,
/// displacement × inverseStep / inverseNodeMass, but no more than the inelastic exchange along the
/// move, at their closing speed there or, if closingAtMoveSpeed, the move's own speed
/// (displacement × inverseStep), whichever is larger. Returns the impulse applied (N s, along
/// -displacement).
/// applied, when not null, sums the impulse.
btScalar applyNodeReaction(btRigidBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity,
                           AppliedImpulse* applied = nullptr, bool closingAtMoveSpeed = false);

/// applyNodeReaction on either kind of dynamic body: a rigid body as above; a multibody link by the
/// same rule, with the link's speed and effective mass along the move from its Jacobian.
btScalar applyNodeReaction(DynamicBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity,
                           bool closingAtMoveSpeed = false);

/// A node that cannot give way (inverse mass 0) at node (m, world) stops tool, whose piece is at
/// pieceNow, short of it over the next step of 1/inverseStep (s): a speculative contact along the
/// nearest face's normal, as Box2D's, that lets the tool's point there close on the node by the
/// gap and no more; from inside (back out by the face nearest the node now), or from past a face
/// its motion over that step reaches the node by (back out by that face), the tool leaves fast
/// enough to be back at the end of that step, as a position solve would move it. The way is read
/// between the tool's two poses, along the arc. The face's plane bounds the node's side of the
/// piece, so the limit is conservative past an edge. forcesPending: the tool's accumulated force
/// and torque are yet to act over that step (in the collision pass, before Bullet's solver adds
/// them). Returns the impulse applied (N s).
btScalar stopShortOfPinnedNode(btRigidBody& tool, const ToolModel& piece, const Pose& pieceNow, const Vec3& node,
                               Real inverseStep, bool forcesPending, AppliedImpulse* applied = nullptr);

/// stopShortOfPinnedNode for either kind of dynamic body. A multibody link gets the speculative
/// contact alone: its pose at the step's end is the multibody's to integrate, with its joints, and
/// its pending forces act through them, so neither is predicted here.
btScalar stopShortOfPinnedNode(DynamicBody& tool, const ToolModel& piece, const Pose& pieceNow, const Vec3& node,
                               Real inverseStep, bool forcesPending);

/// stopShortOfPinnedNode at every pinned node forEachPinned(visit) visits, visit(piece, pieceNow,
/// node) with node in world. A stop at one node can turn the tool into another, of the same piece
/// or of another piece of the tool: the nodes are swept until no stop applies more than a settled
/// impulse, at most 64 times. Most settle in one or two sweeps; a tool that turns far in the step
/// settles slowly, since an impulse's effect on where it ends is read about its pose now (jaws
/// spinning at 130 rad/s came 21% nearer to a pinned node's side each sweep: generated seed 8609
/// with friction; eight sweeps left them through it).
template <typename ForEachPinned>
void stopShortOfPinnedNodes(DynamicBody& tool, const ForEachPinned& forEachPinned, Real inverseStep,
                            bool forcesPending) {
  constexpr int kMostSweeps = 64;
  constexpr btScalar kSettledImpulse = btScalar(1e-7);  // N s
  for (int sweep = 0; sweep < kMostSweeps; ++sweep) {
    btScalar largest = 0;
    forEachPinned([&](const ToolModel& piece, const Pose& pieceNow, const Vec3& node) {
      const btScalar impulse = stopShortOfPinnedNode(tool, piece, pieceNow, node, inverseStep, forcesPending);
      if (impulse > largest) largest = impulse;
    });
    if (largest <= kSettledImpulse) break;
  }
}

}  // namespace thintool::detail
