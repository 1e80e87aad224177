// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SoftSurface.h"

#include <thintool/bullet/Convert.h>
#include <thintool/geometry/RayTriangle.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyInternals.h>

#include <algorithm>
#include <utility>

namespace thintool::detail {

namespace {

Aabb toAabb(const btDbvtVolume& volume) { return {toVec3(volume.Mins()), toVec3(volume.Maxs())}; }

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
  if (root == nullptr) {
    return;
  }
  stack.clear();
  stack.push_back(root);
  while (!stack.empty()) {
    const btDbvtNode* node = stack.back();
    stack.pop_back();
    if (!test(toAabb(node->volume))) {
      continue;
    }
    if (node->isleaf()) {
      if (!leaf(node)) {
        return;
      }
    } else {
      stack.push_back(node->childs[0]);
      stack.push_back(node->childs[1]);
    }
  }
}

}  // namespace

void ensureFaceTree(btSoftBody& softBody) {
  if (!softBody.m_fdbvt.empty() || softBody.m_faces.size() == 0) {
    return;
  }
  for (int i = 0; i < softBody.m_faces.size(); ++i) {
    btSoftBody::Face& face = softBody.m_faces[i];
    face.m_leaf = softBody.m_fdbvt.insert(VolumeOf(face, 0), &face);
  }
  // The default threshold hands groups of up to 128 leaves to a cubic bottom-up pass.
  softBody.m_fdbvt.optimizeTopDown(8);
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

void gatherPatch(btSoftBody& softBody, const Aabb& worldBox, PairState& state) {
  SoftPatch& patch = state.patch;
  patch.clear();
  if (state.patchVertexOfNode.size() != static_cast<std::size_t>(softBody.m_nodes.size())) {
    state.patchVertexOfNode.assign(softBody.m_nodes.size(), kInvalidIndex);
  }
  walk(softBody.m_fdbvt.m_root, state.traversalStack, [&](const Aabb& box) { return box.overlaps(worldBox); },
       [&](const btDbvtNode* leaf) {
         const auto* face = static_cast<const btSoftBody::Face*>(leaf->data);
         // Bullet grows its leaf volumes by the soft margin and the face's velocity, so with a
         // realistic 50 mm margin they overlap the box from several faces away: the face's own
         // motion (start, predicted end, and where ThinTool left its nodes last step) decides.
         // A face with a non-finite node is gathered all the same: detection skips and counts it.
         Aabb motionBox;
         bool finite = true;
         std::array<Index, 3> ids;
         for (int k = 0; k < 3; ++k) {
           const btSoftBody::Node* node = face->m_n[k];
           const Vec3 end = toVec3(node->m_x);
           const Vec3 start = toVec3(node->m_q);
           finite = finite && isFinite(end) && isFinite(start);
           motionBox.include(end);
           motionBox.include(start);
           ids[k] = nodeIndex(softBody, node);
           if (state.lastStep[ids[k]] == state.step) {
             motionBox.include(state.lastPositions[ids[k]]);
           }
         }
         if (finite && !motionBox.overlaps(worldBox)) {
           return true;
         }
         std::array<Index, 3> corners;
         for (int k = 0; k < 3; ++k) {
           const btSoftBody::Node* node = face->m_n[k];
           const Index id = ids[k];
           Index& vertex = state.patchVertexOfNode[id];
           if (vertex == kInvalidIndex) {
             vertex = patch.vertexCount();
             patch.positions.push_back(toVec3(node->m_x));
             patch.previousPositions.push_back(toVec3(node->m_q));
             patch.inverseMasses.push_back(node->m_im);
             patch.nodeIds.push_back(id);
           }
           corners[k] = vertex;
         }
         patch.faces.push_back(corners);
         patch.faceIds.push_back(faceIndex(softBody, face));
         return true;
       });
}

void releasePatch(PairState& state) {
  for (Index id : state.patch.nodeIds) {
    state.patchVertexOfNode[id] = kInvalidIndex;
  }
}

bool SoftBodyRayQuery::anyHit(const Vec3& from, const Vec3& delta) const {
  const SegmentSlab slab(from, delta);
  bool found = false;
  walk(m_softBody.m_fdbvt.m_root, m_stack, [&](const Aabb& box) { return slab.overlaps(box); },
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
