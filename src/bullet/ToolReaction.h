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

#include <LinearMath/btVector3.h>

class btRigidBody;

namespace thintool::detail {

/// Applies to tool the reaction of a node of inverse mass inverseNodeMass (1/kg; 0 for a node that
/// cannot give way) that moved at nodeVelocity (m/s, world) before ThinTool moved it by
/// displacement (m) to nodePosition in a step of inverseStep (1/s): the node's change of momentum,
/// displacement × inverseStep / inverseNodeMass, but no more than the inelastic exchange along the
/// move. Returns the impulse applied (N s, along -displacement).
btScalar applyNodeReaction(btRigidBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity);

}  // namespace thintool::detail
