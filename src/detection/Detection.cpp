// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "detection/Detection.h"

#include "geometry/RayTriangle.h"

#include <thintool/core/Assert.h>

#include <algorithm>
#include <limits>

namespace thintool {

namespace {
constexpr Real kNoHit = std::numeric_limits<Real>::max();
}  // namespace

void DetectionCounters::accumulate(const DetectionCounters& o) {
  facesGathered += o.facesGathered;
  facesWalked += o.facesWalked;
  nodesTested += o.nodesTested;
  triangleTests += o.triangleTests;
  candidates += o.candidates;
  colliding += o.colliding;
  excludedByCheck1 += o.excludedByCheck1;
  excludedByCheck2 += o.excludedByCheck2;
  skippedFaces += o.skippedFaces;
  maxDepth = std::max(maxDepth, o.maxDepth);
}

void PairHistory::reset() {
  for (Index node : m_blockedList) {
    m_blocked[node] = 0;
  }
  m_blockedList.clear();
}

void PairHistory::record(const ToolModel& model, const std::vector<PatchContact>& contacts) {
  if (m_blocked.size() != model.nodeCount()) {
    m_blocked.assign(model.nodeCount(), 0);
    m_blockedList.clear();
    m_blockedList.reserve(model.nodeCount());
  }
  reset();
  for (const PatchContact& contact : contacts) {
    const Index node = contact.toolNode;
    for (Index k = model.oppositeBegin[node]; k < model.oppositeBegin[node + 1]; ++k) {
      const Index opposite = model.opposites[k];
      if (m_blocked[opposite] == 0) {
        m_blocked[opposite] = 1;
        m_blockedList.push_back(opposite);
      }
    }
  }
}

void DetectionWorkspace::prepare(Index n) {
  m_bestDistance.assign(n, kNoHit);
  m_bestFace.assign(n, kInvalidIndex);
  m_bestU.assign(n, 0);
  m_bestV.assign(n, 0);
  m_visited.assign(n, 0);
  m_visitedList.clear();
  m_visitedList.reserve(n);
}

void detectContacts(const StepContext& step, const SoftPatch& patch, const DetectionInput& input,
                    PairHistory& history, DetectionResult& out) {
  THINTOOL_ASSERT(patch.consistent());
  const ToolModel& model = step.model;
  const Pose& toolPose = step.pose;
  const Real skin = step.skin;
  const SoftSurfaceRayQuery* reverseQuery = input.reverseQuery;
  DetectionWorkspace& work = out.workspace;
  std::vector<PatchContact>& outContacts = out.contacts;
  DetectionCounters& outCounters = out.counters;
  outContacts.clear();
  outCounters = DetectionCounters{};
  outCounters.facesGathered = patch.faceCount();
  if (work.m_bestDistance.size() < model.nodeCount()) {
    work.prepare(model.nodeCount());
  }
  out.excludedNodes[0].clear();
  out.excludedNodes[1].clear();

  // Soft vertices into the tool's frame, where the rays and their tree are fixed.
  const Index vertexCount = patch.vertexCount();
  work.m_localPositions.resize(vertexCount);
  work.m_localValid.resize(vertexCount);
  for (Index v = 0; v < vertexCount; ++v) {
    const Vec3& world = patch.positions[v];
    work.m_localValid[v] = isFinite(world) ? 1 : 0;
    work.m_localPositions[v] = toolPose.applyInverse(world);
  }

  // Every face against the rays whose boxes it overlaps; each ray keeps its closest face.
  for (Index f = 0; f < patch.faceCount(); ++f) {
    const auto& corners = patch.faces[f];
    if (!work.m_localValid[corners[0]] || !work.m_localValid[corners[1]] || !work.m_localValid[corners[2]]) {
      ++outCounters.skippedFaces;
      continue;
    }
    const Vec3& a = work.m_localPositions[corners[0]];
    const Vec3& b = work.m_localPositions[corners[1]];
    const Vec3& c = work.m_localPositions[corners[2]];
    Aabb faceBox = Aabb::fromPoints(a, b);
    faceBox.include(c);
    model.rayTree.queryOverlap(faceBox.expanded(skin), [&](Index node) {
      if (!work.m_visited[node]) {
        work.m_visited[node] = 1;
        work.m_visitedList.push_back(node);
      }
      const Vec3& normal = model.normals[node];
      const Real reach = skin + model.probeLengths[node];
      const Vec3 origin = model.positions[node] + normal * skin;
      ++outCounters.triangleTests;
      const SegmentTriangleHit hit = intersectSegmentTriangle(origin, normal * -reach, a, b, c);
      const Real distance = hit.t * reach;
      if (hit.hit && distance < work.m_bestDistance[node]) {
        work.m_bestDistance[node] = distance;
        work.m_bestFace[node] = f;
        work.m_bestU[node] = hit.u;
        work.m_bestV[node] = hit.v;
      }
    });
  }

  // Filters, in the paper's order, on the nodes whose ray found a face.
  const bool useCheck1 = input.filters.check1;
  const bool useCheck2 = input.filters.check2 && patch.orientation != 0;
  const bool useReverseRay = useCheck2 && input.filters.reverseRay && reverseQuery != nullptr;
  const Real orientation = patch.orientation >= 0 ? 1 : -1;
  outCounters.nodesTested = static_cast<Index>(work.m_visitedList.size());
  // Sorted so that contacts come out in node order whatever order the faces arrived in.
  std::sort(work.m_visitedList.begin(), work.m_visitedList.end());
  for (Index node : work.m_visitedList) {
    const Real distance = work.m_bestDistance[node];
    const Index face = work.m_bestFace[node];
    if (distance == kNoHit) {
      continue;
    }
    ++outCounters.candidates;
    if (useCheck1 && history.isBlocked(node)) {
      ++outCounters.excludedByCheck1;
      out.excludedNodes[0].push_back(node);
      continue;
    }
    const Vec3& normal = model.normals[node];
    if (useCheck2) {
      const auto& corners = patch.faces[face];
      const Vec3 faceNormal = triangleNormal(work.m_localPositions[corners[0]], work.m_localPositions[corners[1]],
                                             work.m_localPositions[corners[2]]) *
                              orientation;
      if (dot(faceNormal, normal) >= 0) {
        ++outCounters.excludedByCheck2;
        out.excludedNodes[1].push_back(node);
        continue;
      }
      if (useReverseRay) {
        const Vec3 from = toolPose.apply(model.positions[node]);
        const Vec3 delta = toolPose.applyToDirection(normal) * input.reverseRayLength;
        if (!reverseQuery->anyHit(from, delta)) {
          ++outCounters.excludedByCheck2;
          out.excludedNodes[1].push_back(node);
          continue;
        }
      }
    }
    PatchContact contact;
    contact.kind = ContactKind::ToolRay;
    contact.toolNode = node;
    contact.patchFace = face;
    contact.softFace = patch.faceIds[face];
    contact.softNodeCount = 3;
    for (int k = 0; k < 3; ++k) {
      contact.patchVertices[k] = patch.faces[face][k];
      contact.softNodes[k] = patch.nodeIds[patch.faces[face][k]];
    }
    const Real u = work.m_bestU[node];
    const Real v = work.m_bestV[node];
    contact.barycentric = {1 - u - v, u, v};
    contact.depth = distance - skin;
    contact.normal = toolPose.applyToDirection(normal);
    contact.point = toolPose.apply(model.positions[node] - normal * contact.depth);
    contact.offset = -dot(contact.normal, toolPose.apply(model.positions[node]) + contact.normal * skin);
    outCounters.maxDepth = std::max(outCounters.maxDepth, contact.depth);
    outContacts.push_back(contact);
  }
  outCounters.colliding = static_cast<Index>(outContacts.size());

  for (Index node : work.m_visitedList) {
    work.m_visited[node] = 0;
    work.m_bestDistance[node] = kNoHit;
  }
  work.m_visitedList.clear();

  if (useCheck1) {
    history.record(model, outContacts);
  }
}

}  // namespace thintool
