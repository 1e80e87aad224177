// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What the soft body does about this step's contacts.
///
/// - ResponseKind::Constraint (default): a position projection after position-based dynamics
///   (Müller et al., "Position based dynamics", 2007), in four stages, and friction:
///   - leaving through the entry plane: every soft node of a hit face that lies inside the tool
///     (its faces' planes moved out by the skin) leaves through the entry plane of one of its
///     face's contacts, the one it is least behind: never across the tool, never out of its far
///     side;
///   - the node guard, beyond the paper: any other soft node near the tool that ends inside it
///     (it slipped in between the rays, at a rim) leaves through the face it was outside of at
///     the start of the step, judged in the tool's previous pose, so it too returns to the side
///     it came from;
///   - the contact points onto their planes: each contact moves the point where its ray met the
///     soft face onto its entry plane; the move is shared by the face's nodes in proportion to
///     barycentric weight × inverse mass, the smallest mass-weighted move that does it, so a
///     needle pressing the middle of a large face moves the face and a node far from the hit point
///     moves little; but beside a pinned node no node moves further than the point itself, nor
///     past the contact's plane, so the point then moves only part of the way, rather than fling
///     the free node a hundred times the depth, or push it again at every contact and sweep.
///     Contacts are swept in order (Gauss–Seidel) until every hit point is out, or four times;
///   - carried nodes back: no move may end inside the tool. Moving a face's nodes along the face's
///     normal can, near a rim, carry one into the tool from a side no contact speaks for, or across
///     the tool or round its rim; such a node goes back to the face it was outside of at the start
///     of the step, as the node guard sends it;
///   then, when FrictionSettings::enabled, Coulomb friction on the moved nodes (see there).
///   The skin is kept whole by every point that began the step beyond it, and by every face's or
///   edge's contact point. A soft node that began the step inside the skin (outside the tool) keeps
///   only where it began plus skinGrowthSpeed·dt: its way out of the tool is immediate, its way
///   back to the full skin at bounded speed, as Box2D v3.0 bounds the speed at which contacts push
///   overlapping bodies apart (b2WorldDef::contactPushoutVelocity). Put back to the full skin at
///   once, a node that the soft solve pulls into the skin every step would bounce between the solve
///   and the projection at skin/dt.
/// - ResponseKind::PaperForce: the paper's eq. (2), f = k·t along the contact normal, t being the
///   penetration into the tool's skin, spread over the face's nodes by the hit's barycentric
///   weights. Bullet's classic solver clears node forces before collisions are processed, so a
///   force added then is lost, and one added after the step acts a step late. We apply f as the
///   displacement it causes within the step under Bullet's symplectic Euler, Δx = f·m⁻¹·dt², so
///   it acts in the step it was found in. Like any explicit penalty it is stable only while
///   k·dt²/m stays small (about < 1 for a node alone).
/// - ResponseKind::None: contacts are reported, nothing is moved.

#include "detection/Detection.h"
#include "tool/StepContext.h"

#include <thintool/response/ResponseTypes.h>

#include <vector>

namespace thintool {

/// A soft node's move, and the direction it was moved out along.
struct NodeCorrection {
  Index vertex = kInvalidIndex;  ///< index in SoftPatch::positions
  Vec3 displacement;             ///< world (m)
  Vec3 normal;                   ///< world, unit, out of the tool: the direction the node must not go back along
  bool sticks = false;           ///< friction holds it to the tool's surface (static friction)
};

/// A plane a soft node must not cross during the soft solver's iterations: dot(normal, x) + offset
/// >= 0 (world). The glue turns each into a one-sided contact of Bullet's solver.
struct NodeHold {
  Index vertex = kInvalidIndex;  ///< index in SoftPatch::positions
  Vec3 normal;
  Real offset = 0;
  bool sticks = false;  ///< the solver also keeps the node from sliding along the plane
};

struct ResponseResult;

/// The response's scratch, kept from call to call so that a step allocates nothing once it has
/// grown to the patch.
class ResponseWorkspace {
 private:
  friend struct ResponseProjection;
  friend void computeHolds(const StepContext&, const SoftPatch&, bool, ResponseResult&, std::vector<NodeHold>&);
  std::vector<Vec3> m_positions;
  std::vector<Index> m_slot;          ///< per patch vertex: its entry in the output, or kInvalidIndex
  std::vector<Real> m_largestShare;   ///< per output entry: the largest single move, whose normal it keeps
  std::vector<Real> m_entryDepth;     ///< per output entry: how far inside the tool the node was
  std::vector<Real> m_contactSkinLeft;  ///< per contact: how much of the skin its point does not keep this step
};

/// What the response did in a step, and the scratch it did it with.
struct ResponseResult {
  std::vector<NodeCorrection> corrections;
  Wrench wrench;  ///< on the tool; torque about the tool's origin
  /// Corrections dropped as faults: not finite, or longer than the step can justify (the node's
  /// own motion back, across the piece and its skin, and the piece's travel). Never expected.
  Index rejected = 0;
  ResponseWorkspace workspace;
};

/// Turns contacts into node corrections and the wrench on the tool over the step. The context's
/// previousPose is where the tool was at the start of the step (the node guard reads
/// SoftPatch::previousPositions against it); a node that began the step inside the skin returns to
/// it at the context's skinGrowthSpeed. Nodes of zero inverse mass (pinned) are never moved.
/// Allocates nothing once the result has grown to the patch.
void computeResponse(const StepContext& step, const SoftPatch& patch, const std::vector<PatchContact>& contacts,
                     const ResponseSettings& settings, ResponseResult& out);

/// The planes that keep the soft solver from undoing the response, or from dragging a node through
/// the tool while it repairs a deformed body: each moved node keeps the plane it was moved onto
/// (along its correction's normal, through where it now is). With holdAtToolFaces, every movable node
/// of the patch outside the tool grown by the skin, moved or not, also keeps the plane of a tool
/// face it is in front of, which separates it from the tool (a moved node's own plane may be a soft
/// face's, across the tool's face): of the faces it was also in front of at the start of the step
/// (previousPositions, the context's previousPose), the one it is farthest in front of, so that a node the
/// tool passed beside a rim is held beside the rim, not behind the face on the tool's far side from
/// where it came; chosen anew each step, it still lets a node wrap around a rim over several steps.
/// Ask for it only where every node is known to be on its own side of the tool, as after swept
/// detection: a node that slipped through unseen would be held on the wrong side.
void computeHolds(const StepContext& step, const SoftPatch& patch, bool holdAtToolFaces, ResponseResult& response,
                  std::vector<NodeHold>& outHolds);

}  // namespace thintool
