// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SoftSurface.h"

#include "geometry/RayTriangle.h"

#include <thintool/bullet/Convert.h>
#include <thintool/core/Assert.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyInternals.h>
#include <BulletSoftBody/btSoftBodySolvers.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace thintool::detail {

namespace {

Aabb toAabb(const btDbvtVolume& volume) { return {toVec3(volume.Mins()), toVec3(volume.Maxs())}; }

// The box in Bullet's scalar, rounded outwards, so that a walk by it misses nothing the box meets.
btDbvtVolume toVolume(const Aabb& box) {
  btVector3 low = toBt(box.min);
  btVector3 high = toBt(box.max);
  for (int axis = 0; axis < 3; ++axis) {
    low[axis] = std::nextafter(low[axis], -std::numeric_limits<btScalar>::infinity());
    high[axis] = std::nextafter(high[axis], std::numeric_limits<btScalar>::infinity());
  }
  return btDbvtVolume::FromMM(low, high);
}

inline void prefetch(const void* address) {
#if defined(__GNUC__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

Index faceIndex(const btSoftBody& softBody, const btSoftBody::Face* face) {
  return static_cast<Index>(face - &softBody.m_faces[0]);
}

Index nodeIndex(const btSoftBody& softBody, const btSoftBody::Node* node) {
  return static_cast<Index>(node - &softBody.m_nodes[0]);
}

// Depth-first walk of a btDbvt, calling leaf(node) for the leaves whose volumes pass test. Stops
// when leaf returns false. The stack is the caller's, so that a warmed-up walk allocates nothing.
template <class Test, class Leaf>
void walk(const btDbvtNode* root, std::vector<const btDbvtNode*>& stack, const Test& test, const Leaf& leaf) {
  stack.clear();
  if (root == nullptr) {
    return;
  }
  stack.push_back(root);
  while (!stack.empty()) {
    const btDbvtNode* node = stack.back();
    stack.pop_back();
    if (!test(node->volume)) {
      continue;
    }
    if (node->isleaf()) {
      if (!leaf(node)) {
        return;
      }
    } else {
      // Bullet allocates its tree nodes one by one: ask for both children's memory now, so that
      // the one tested second arrives while the first is being tested.
      prefetch(node->childs[0]);
      prefetch(node->childs[1]);
      stack.push_back(node->childs[0]);
      stack.push_back(node->childs[1]);
    }
  }
}

// Adds the face to state.patch when its own motion meets toolBox: where it starts, where it is
// predicted to end, and where ThinTool left its nodes last step. A face with a non-finite node is
// gathered all the same: detection skips and counts it. Raises largestSquared to the squared
// largest move of a node it adds.
void gatherFace(const btSoftBody& softBody, Index faceId, const Aabb& toolBox, PairState& state,
                Real& largestSquared) {
  const btSoftBody::Face& face = softBody.m_faces[static_cast<int>(faceId)];
  Aabb motionBox;
  bool finite = true;
  std::array<Index, 3> ids;
  std::array<Vec3, 3> ends;
  std::array<Vec3, 3> starts;
  for (int k = 0; k < 3; ++k) {
    const btSoftBody::Node* node = face.m_n[k];
    // The deformable world predicts into m_q and keeps the start in m_x; the classic ones the other
    // way round.
    ends[k] = toVec3(state.feedsDeformable ? node->m_q : node->m_x);
    starts[k] = toVec3(state.feedsDeformable ? node->m_x : node->m_q);
    finite = finite && isFinite(ends[k]) && isFinite(starts[k]);
    motionBox.include(ends[k]);
    motionBox.include(starts[k]);
    ids[k] = nodeIndex(softBody, node);
    if (state.sweptNodes.stampedLastStep(ids[k])) {
      motionBox.include(state.lastPositions[ids[k]]);
    }
  }
  if (finite && !motionBox.overlaps(toolBox)) {
    return;
  }
  SoftPatch& patch = state.patch;
  std::array<Index, 3> corners;
  for (int k = 0; k < 3; ++k) {
    const Index id = ids[k];
    Index& vertex = state.patchVertexOfNode[id];
    if (vertex == kInvalidIndex) {
      vertex = patch.vertexCount();
      patch.positions.push_back(ends[k]);
      patch.previousPositions.push_back(starts[k]);
      patch.inverseMasses.push_back(face.m_n[k]->m_im);
      patch.nodeIds.push_back(id);
      Real moved = lengthSquared(ends[k] - starts[k]);
      if (state.sweptNodes.stampedLastStep(id)) {
        moved = std::max(moved, lengthSquared(ends[k] - state.lastPositions[id]));
      }
      if (moved > largestSquared) {  // false for NaN
        largestSquared = moved;
      }
    }
    corners[k] = vertex;
  }
  patch.faces.push_back(corners);
  patch.faceIds.push_back(faceId);
}

}  // namespace

bool ignores(const btSoftBody& softBody, const btCollisionObject& body) {
  return softBody.m_collisionDisabledObjects.findLinearSearch(&body) != softBody.m_collisionDisabledObjects.size();
}

// Bullet's handler picks the soft body's rigid contact by its flags under RVSmask, one kind at a
// time; ThinTool stands in for the node contact (SDF_RS) of the classic solver only.
StockReason stockReason(const btSoftBody& softBody) {
  const btSoftBodySolver* solver = softBody.getSoftBodySolver();
  if (solver == nullptr || solver->getSolverType() != btSoftBodySolver::DEFAULT_SOLVER) {
    return StockReason::DeformableWorld;
  }
  const int asked = softBody.m_cfg.collisions & btSoftBody::fCollision::RVSmask;
  if ((asked & btSoftBody::fCollision::CL_RS) != 0) {
    return StockReason::ClusterCollision;
  }
  if (asked != btSoftBody::fCollision::SDF_RS) {
    return StockReason::NoRigidContact;
  }
  return softBody.m_faces.size() == 0 ? StockReason::NoFaces : StockReason::None;
}

bool ensureFaceTree(btSoftBody& softBody) {
  if (!softBody.m_fdbvt.empty() || softBody.m_faces.size() == 0) {
    return false;
  }
  for (int i = 0; i < softBody.m_faces.size(); ++i) {
    btSoftBody::Face& face = softBody.m_faces[i];
    face.m_leaf = softBody.m_fdbvt.insert(VolumeOf(face, 0), &face);
  }
  // The default threshold hands groups of up to 128 leaves to a cubic bottom-up pass.
  softBody.m_fdbvt.optimizeTopDown(8);
  return true;
}

Real faceLeafSlack(const btSoftBody& softBody, Real nodeTravel) {
  // predictMotion clears the face tree while m_bUpdateRtCst is set and clears the flag; until then
  // its fitting margin (m_sst.radmrg) has not even been set.
  const bool fitted = !softBody.m_bUpdateRtCst;
  const bool poseMatched = softBody.m_pose.m_bframe && softBody.m_cfg.kMT > 0;
  if (!fitted || poseMatched) {
    return 0;
  }
  const Real margin = std::min<Real>(softBody.m_sst.radmrg, softBody.getCollisionShape()->getMargin());
  const Real slack = std::max<Real>(margin, 0) - nodeTravel;
  return std::isfinite(slack) ? slack : 0;
}

int surfaceOrientation(const btSoftBody& softBody) {
  const int faceCount = softBody.m_faces.size();
  if (faceCount < 4) {
    return 0;
  }
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(3 * static_cast<std::size_t>(faceCount));
  Real sixVolume = 0;
  for (int i = 0; i < faceCount; ++i) {
    const btSoftBody::Face& face = softBody.m_faces[i];
    Index corner[3];
    for (int k = 0; k < 3; ++k) {
      corner[k] = nodeIndex(softBody, face.m_n[k]);
    }
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(std::min(corner[k], corner[(k + 1) % 3]), std::max(corner[k], corner[(k + 1) % 3]));
    }
    sixVolume += dot(toVec3(face.m_n[0]->m_x), cross(toVec3(face.m_n[1]->m_x), toVec3(face.m_n[2]->m_x)));
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k < edges.size();) {
    std::size_t run = k;
    while (run < edges.size() && edges[run] == edges[k]) {
      ++run;
    }
    if (run - k != 2) {
      return 0;
    }
    k = run;
  }
  if (sixVolume > 0) return 1;
  if (sixVolume < 0) return -1;
  return 0;
}

namespace {

// The rounding allowance for a box compared with Bullet's volumes, which it rounded in btScalar.
Real roundingOf(const Aabb& box) {
  const Real magnitude = std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z),
                                   std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z)});
  return 4 * Real(std::numeric_limits<btScalar>::epsilon()) * (1 + magnitude);
}

// The gather's runs: listFaces(bound) puts the candidate faces for the tool's box grown by bound in
// state.candidateFaces, and each of them whose motion meets the box joins the patch. Returns the
// candidates over all runs.
template <class ListFaces>
Index gatherCandidates(btSoftBody& softBody, const Aabb& toolBox, Real displacementBound, bool widen,
                       PairState& state, const ListFaces& listFaces) {
  Index listed = 0;
  SoftPatch& patch = state.patch;
  if (state.patchVertexOfNode.size() != static_cast<std::size_t>(softBody.m_nodes.size())) {
    state.patchVertexOfNode.assign(softBody.m_nodes.size(), kInvalidIndex);
  }
  // A walk lists faces by where they end the step; a face that starts near the tool and ends away
  // from it lies up to its displacement farther out. (A scan lists by the whole motion.)
  Real bound = std::max<Real>(displacementBound, 0);
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (attempt > 0) {
      releasePatch(state);
    }
    patch.clear();
    Real largestSquared = 0;
    state.candidateFaces.clear();
    listFaces(bound);
    // The faces' nodes are read a few faces ahead of their use, which hides the wait for memory
    // that reading them one face at a time would add to each face: soft nodes lie scattered.
    constexpr std::size_t kLookAhead = 8;
    const std::size_t candidateCount = state.candidateFaces.size();
    listed += static_cast<Index>(candidateCount);
    for (std::size_t c = 0; c < candidateCount; ++c) {
      if (c + kLookAhead < candidateCount) {
        const btSoftBody::Face& ahead = softBody.m_faces[static_cast<int>(state.candidateFaces[c + kLookAhead])];
        for (const btSoftBody::Node* node : ahead.m_n) {
          prefetch(&node->m_x);
        }
      }
      gatherFace(softBody, state.candidateFaces[c], toolBox, state, largestSquared);
    }
    // Gathered nodes that moved farther than the walk allowed for: their neighbours may have too.
    const Real largestDisplacement = std::sqrt(largestSquared);
    if (!widen || largestDisplacement <= bound) {
      break;
    }
    bound = 2 * largestDisplacement;
  }
  return listed;
}

}  // namespace

Index gatherPatch(btSoftBody& softBody, const Aabb& toolBox, Real displacementBound, Real leafSlack, bool widen,
                  PairState& state) {
  return gatherCandidates(softBody, toolBox, displacementBound, widen, state, [&](Real bound) {
    // A leaf spans its face grown by the slack, so shrinking the walk's box by the slack keeps
    // every leaf whose face meets the grown box; Bullet rounded the leaf in btScalar, which the
    // rounding allowance covers. The test compares interval ends only, so it stays right for a
    // box shrunk past empty.
    const Aabb grown = toolBox.expanded(bound);
    const btDbvtVolume walkBox = toVolume(grown.expanded(roundingOf(grown) - leafSlack));
    walk(softBody.m_fdbvt.m_root, state.traversalStack,
         [&](const btDbvtVolume& volume) { return Intersect(volume, walkBox); },
         [&](const btDbvtNode* leaf) {
           prefetch(leaf->data);
           state.candidateFaces.push_back(faceIndex(softBody, static_cast<const btSoftBody::Face*>(leaf->data)));
           return true;
         });
  });
}

void readFaceCorners(const btSoftBody& softBody, std::vector<std::array<Index, 3>>& corners) {
  corners.resize(static_cast<std::size_t>(softBody.m_faces.size()));
  for (int f = 0; f < softBody.m_faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      corners[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] =
          nodeIndex(softBody, softBody.m_faces[f].m_n[k]);
    }
  }
}

Index gatherPatchByScan(btSoftBody& softBody, const Aabb& toolBox, PairState& state) {
  const int faceCount = softBody.m_faces.size();
  THINTOOL_ASSERT(state.faceCorners.size() == static_cast<std::size_t>(faceCount));
  return gatherCandidates(softBody, toolBox, 0, false, state, [&](Real /*bound*/) {
    if (faceCount == 0) return;
    // The corners come from the pair's compact copy of the faces' node indices, not from Bullet's
    // faces, whose size would make the scan read several times the memory; the nodes are asked
    // for a few faces ahead.
    const btSoftBody::Node* nodes = &softBody.m_nodes[0];
    constexpr int kLookAhead = 8;
    for (int f = 0; f < faceCount; ++f) {
      if (f + kLookAhead < faceCount) {
        for (const Index n : state.faceCorners[static_cast<std::size_t>(f + kLookAhead)]) prefetch(&nodes[n].m_x);
      }
      const std::array<Index, 3>& corners = state.faceCorners[static_cast<std::size_t>(f)];
      // The box of the face's motion, as gatherFace bounds it. A face with a node that is not
      // finite is listed all the same: detection skips and counts it.
      btVector3 low = nodes[corners[0]].m_x;
      btVector3 high = low;
      bool finite = true;
      for (const Index n : corners) {
        const btSoftBody::Node& node = nodes[n];
        low.setMin(node.m_x);
        low.setMin(node.m_q);
        high.setMax(node.m_x);
        high.setMax(node.m_q);
        finite = finite && std::isfinite(node.m_x.length2() + node.m_q.length2());
      }
      Aabb motion{toVec3(low), toVec3(high)};
      for (const Index n : corners) {
        if (state.sweptNodes.stampedLastStep(n)) motion.include(state.lastPositions[n]);
      }
      if (!finite || motion.overlaps(toolBox)) state.candidateFaces.push_back(static_cast<Index>(f));
    }
  });
}

Real softBodyMotion(const btSoftBody& softBody, PairState& state) {
  // Bullet refits the node tree in every predictMotion, around each node's end of step grown by the
  // margin (and ahead along its velocity).
  const btDbvtNode* root = softBody.m_ndbvt.m_root;
  if (root == nullptr) {
    return 0;
  }
  const Aabb bounds = toAabb(root->volume);
  Real motionSquared = 0;
  if (state.hasSoftBounds) {
    Vec3 shift;
    for (int axis = 0; axis < 3; ++axis) {
      shift[axis] = std::max(std::abs(bounds.min[axis] - state.softBounds.min[axis]),
                             std::abs(bounds.max[axis] - state.softBounds.max[axis]));
    }
    motionSquared = lengthSquared(shift);
  } else {
    for (int i = 0; i < softBody.m_nodes.size(); ++i) {
      const btSoftBody::Node& node = softBody.m_nodes[i];
      motionSquared = std::max(motionSquared, lengthSquared(toVec3(node.m_x) - toVec3(node.m_q)));
    }
  }
  state.softBounds = bounds;
  state.hasSoftBounds = true;
  return std::isfinite(motionSquared) ? std::sqrt(motionSquared) : 0;
}

void releasePatch(PairState& state) {
  for (Index id : state.patch.nodeIds) {
    state.patchVertexOfNode[id] = kInvalidIndex;
  }
}

bool SoftBodyRayQuery::anyHit(const Vec3& from, const Vec3& delta) const {
  const SegmentSlab slab(from, delta);
  bool found = false;
  walk(m_softBody.m_fdbvt.m_root, m_stack, [&](const btDbvtVolume& volume) { return slab.overlaps(toAabb(volume)); },
       [&](const btDbvtNode* leaf) {
         const auto* face = static_cast<const btSoftBody::Face*>(leaf->data);
         found = intersectSegmentTriangle(from, delta, toVec3(face->m_n[0]->m_x), toVec3(face->m_n[1]->m_x),
                                          toVec3(face->m_n[2]->m_x))
                     .hit;
         return !found;
       });
  return found;
}

}  // namespace thintool::detail
