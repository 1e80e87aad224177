// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// Reading a btSoftBody's surface near a tool into the core's plain data. The gather walks the soft
// body's face tree (btSoftBody::m_fdbvt), which the glue builds if absent, so that only faces near
// the tool are visited; Bullet then refits every leaf of it in each predictMotion. Swept detection
// with BulletSettings::scanFaces builds none and scans every face's motion instead, which costs a
// whole step less than that refit (benchmarks/bullet/WholeStepBench.cpp).

#include "PairState.h"

#include "detection/SoftPatch.h"
#include "geometry/Aabb.h"

#include <vector>

class btCollisionObject;
class btSoftBody;
struct btDbvtNode;

namespace thintool::detail {

/// As Bullet's own handler: a soft body ignores the bodies in its m_collisionDisabledObjects.
bool ignores(const btSoftBody& softBody, const btCollisionObject& body);

/// Why a tool's pair with this soft body is left to Bullet's stock handler, if it is.
StockReason stockReason(const btSoftBody& softBody);

/// Whether the last word keeps the soft body's nodes out of tools: every body whose pairs are
/// ThinTool's, and the faceless ones, which have nodes but nothing for detection to meet.
inline bool lastWordActsOn(StockReason reason) {
  return reason == StockReason::None || reason == StockReason::NoFaces;
}

/// Builds the soft body's face tree if it has none. Bullet keeps a built tree up to date in every
/// predictMotion; its own initializeFaceTree() compares every face with every other (quadratic),
/// so ThinTool inserts the leaves itself and optimises the tree once. True when it built one: its
/// leaves then fit their faces exactly until Bullet next refits them.
bool ensureFaceTree(btSoftBody& softBody);

/// How far each leaf of the soft body's face tree is known to reach beyond its face on every side
/// (m), for a walk to shrink its box by: Bullet's predictMotion fits each leaf around its face grown
/// by the soft margin (lazily, so a leaf may be larger still), and nodeTravel (m) is how far the
/// nodes may have moved since (CollisionPass). Negative when they may have moved out of their
/// leaves: the walk then grows its box by as much. 0, as if the leaves fitted their faces exactly,
/// when how far they moved is unknown: nodeTravel infinite, pose matching after the fit, or a body
/// never predicted since its faces changed.
Real faceLeafSlack(const btSoftBody& softBody, Real nodeTravel);

/// +1 when the closed surface winds counter-clockwise seen from outside, -1 when inverted, 0 when
/// the surface is open (some edge does not have exactly two faces) or encloses no volume.
int surfaceOrientation(const btSoftBody& softBody);

/// Fills state.patch with the faces whose motion in the step overlaps toolBox (world): from the
/// start of the step (m_q) to its predicted end (m_x), and where ThinTool left their nodes last
/// step. Bullet's face tree bounds each face only where it ends, so the walk looks
/// displacementBound (m) beyond toolBox for faces that end away from it; with widen, when a
/// gathered node moved farther, the walk widens and runs again. The walk's box is shrunk by
/// leafSlack (faceLeafSlack), which leaves out only leaves whose faces cannot meet toolBox.
/// state.lastStep and state.lastPositions must be sized to the soft body's nodes. Returns how many
/// faces the walk met, over all its runs.
Index gatherPatch(btSoftBody& softBody, const Aabb& toolBox, Real displacementBound, Real leafSlack, bool widen,
                 PairState& state);

/// Each of the soft body's faces as the indices of its three nodes.
void readFaceCorners(const btSoftBody& softBody, std::vector<std::array<Index, 3>>& corners);

/// Fills state.patch with the faces whose motion in the step meets toolBox, as gatherPatch does,
/// reading every face's nodes instead of walking a tree: each face's start, predicted end and last
/// sweep's end are tested, so that no face is missed however fast it moved. The faces are gathered
/// in the order of their indices. state.faceCorners must hold the soft body's faces
/// (readFaceCorners). Returns the faces listed for the gather.
Index gatherPatchByScan(btSoftBody& softBody, const Aabb& toolBox, PairState& state);

/// How far the soft body as a whole moved this step (m): the largest move of a side of its node
/// tree's bounds since the pair's last step, or, in the pair's first step, the largest move of any
/// node (the only visit of every node, once per pair). Records the bounds in state.
Real softBodyMotion(const btSoftBody& softBody, PairState& state);

/// Clears the soft node -> patch vertex map for the next gather.
void releasePatch(PairState& state);

/// Check 2's reverse ray against the whole soft surface.
class SoftBodyRayQuery final : public SoftSurfaceRayQuery {
 public:
  SoftBodyRayQuery(const btSoftBody& softBody, std::vector<const btDbvtNode*>& stack)
      : m_softBody(softBody), m_stack(stack) {}
  bool anyHit(const Vec3& from, const Vec3& delta) const override;

 private:
  const btSoftBody& m_softBody;
  std::vector<const btDbvtNode*>& m_stack;
};

}  // namespace thintool::detail
