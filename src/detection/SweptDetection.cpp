// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "detection/SweptDetection.h"

#include "geometry/Ccd.h"
#include "geometry/RayTriangle.h"

#include <thintool/core/Assert.h>

#include <algorithm>
#include <cmath>

namespace thintool {

namespace {

// Below this fraction of the tool's size a feature counts as lying on the other one: its side
// cannot be read from the geometry and comes from memory instead.
constexpr Real kOnSurface = 1e-9;

// A soft face whose area is below this fraction of its longest edge squared counts as collapsed:
// float coordinates (Bullet's float build) leave a line of three nodes with about 1e-7 of it.
constexpr Real kCollapsed = 1e-6;

// Relative margin on a comparison of squares that stands in for one of lengths, so that rounding
// in either form cannot make them disagree.
constexpr Real kSquaresMargin = 1e-6;

Aabb boxOf(std::initializer_list<Vec3> points) {
  Aabb box;
  for (const Vec3& p : points) box.include(p);
  return box;
}

Real longestEdgeSquared(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::max({lengthSquared(b - a), lengthSquared(c - b), lengthSquared(a - c)});
}

int signOf(Real value) { return (value > 0) - (value < 0); }

// Barycentric coordinates clamped into the triangle, so that a contact's point lies on the face.
Vec3 clampedBarycentric(Vec3 w) {
  w = {std::max<Real>(w.x, 0), std::max<Real>(w.y, 0), std::max<Real>(w.z, 0)};
  const Real sum = w.x + w.y + w.z;
  return sum > 0 ? w / sum : Vec3{Real(1) / 3, Real(1) / 3, Real(1) / 3};
}

// Everything one call shares, so that the three kinds of test read like the rules they apply.
struct Sweep {
  const ToolModel& model;
  const Pose& pose;
  const SoftPatch& patch;
  Real skin;
  Real onSurface;
  /// How far inside the tool grown by the skin the solver may leave a node it held on that
  /// surface (m), by rounding (4e-9 m seen in Bullet's float build): such a node slid along the
  /// surface and did not enter.
  Real heldOnSurface;
  SideMemory& memory;
  const std::vector<Vec3>& start;
  const std::vector<Vec3>& end;
  /// The piece's poses along its arc, start and end included, when it turns farther in the step
  /// than one sample: arcSamples + 1 of them; 1 reads the chord alone.
  const Pose* arc;
  int arcSamples;
  std::vector<PatchContact>& out;
  DetectionCounters& counters;

  // A contact asking the soft point, made of up to three patch vertices with the given weights,
  // to end on the positive side of the plane through toolPoint (tool frame) with normal
  // direction (tool frame), the skin away.
  void emit(ContactKind kind, const Index* vertices, Index count, const Vec3& weights, const Vec3& toolPoint,
            const Vec3& direction, Real timeOfImpact, Index toolNode, Index toolFeature, Index face) {
    PatchContact contact;
    contact.kind = kind;
    contact.normal = pose.applyToDirection(direction);
    contact.offset = -(dot(contact.normal, pose.apply(toolPoint)) + skin);
    Vec3 point;
    for (Index k = 0; k < count; ++k) {
      contact.patchVertices[k] = vertices[k];
      contact.softNodes[k] = patch.nodeIds[vertices[k]];
      point += patch.positions[vertices[k]] * weights[k];
    }
    const Real clearance = dot(contact.normal, point) + contact.offset;
    if (!(clearance < 0)) {
      return;  // already where it must be
    }
    contact.softNodeCount = count;
    contact.barycentric = weights;
    contact.point = point;
    contact.depth = -clearance - skin;
    contact.timeOfImpact = timeOfImpact;
    contact.toolNode = toolNode;
    contact.toolFeature = toolFeature;
    if (face != kInvalidIndex) {
      contact.patchFace = face;
      contact.softFace = patch.faceIds[face];
    }
    counters.maxDepth = std::max(counters.maxDepth, contact.depth);
    out.push_back(contact);
  }

  // A soft node's segment against the tool grown by the skin; and, before it, the soft solver's
  // move of the node since detection last left it, made while the tool stood at previousPose.
  void softNode(Index v, const Vec3* checked) {
    Index solverEntry = kInvalidIndex;
    if (checked != nullptr) {
      const ClipResult during = clipSegmentConvex(model.planes, skin - heldOnSurface, *checked, start[v]);
      solverEntry = during.hit ? during.enterPlane : kInvalidIndex;
    }
    const ClipResult clip = clipSegmentConvex(model.planes, skin, start[v], end[v]);
    if (!clip.hit && solverEntry == kInvalidIndex) {
      return;
    }
    // Under a turn the chord of the node's path, seen from the piece, can cut through it where the
    // arc never went: a node beside a ball spinning in place. One that ends outside went in only if
    // its arc did too.
    if (solverEntry == kInvalidIndex && arcSamples > 1 && outsideDistance(model.planes, end[v]) > skin &&
        !arcEnters(v)) {
      return;
    }
    ++counters.candidates;
    const Index id = patch.nodeIds[v];
    // The solver pushed it in (or through): it goes back the way it came, wherever it is now.
    Index plane = solverEntry != kInvalidIndex ? solverEntry : clip.enterPlane;
    if (plane == kInvalidIndex) {
      plane = memory.nodeSide(id);
    }
    if (plane == kInvalidIndex) {
      // Inside from the start with no memory: the face it is least inside of.
      outsideDistance(model.planes, start[v], &plane);
    }
    memory.setNodeSide(id, plane);
    const Plane& face = model.planes[plane];
    emit(ContactKind::SoftNode, &v, 1, {1, 0, 0}, face.normal * face.offset, face.normal, clip.enter, kInvalidIndex,
         plane, kInvalidIndex);
  }

  // Whether soft node v's path, its world motion straight and the piece on its arc, meets the piece
  // grown by the skin in some sample of the arc.
  bool arcEnters(Index v) const {
    const Vec3& from = patch.previousPositions[v];
    const Vec3& to = patch.positions[v];
    Vec3 previous = start[v];
    for (int k = 1; k <= arcSamples; ++k) {
      const Vec3 current = k == arcSamples ? end[v] : arc[k].applyInverse(from + (to - from) * (Real(k) / arcSamples));
      if (clipSegmentConvex(model.planes, skin, previous, current).hit) return true;
      previous = current;
    }
    return false;
  }

  // A soft face's motion, read once for all the tool points near it.
  struct FaceMotion {
    Index face = kInvalidIndex;
    const Vec3 *a0 = nullptr, *b0 = nullptr, *c0 = nullptr, *a1 = nullptr, *b1 = nullptr, *c1 = nullptr;
    Vec3 n0, n1;          // unit normals at the start and the end
    bool turned = false;  // the face turned over during the step
    TriangleProjector onEnd;  // projection onto the face where it ends
  };

  bool faceMotion(Index f, FaceMotion& motion) const {
    const auto& corners = patch.faces[f];
    motion = {f, &start[corners[0]], &start[corners[1]], &start[corners[2]], &end[corners[0]], &end[corners[1]],
              &end[corners[2]], {}, {}, false, {}};
    const Vec3 normal0 = triangleNormal(*motion.a0, *motion.b0, *motion.c0);
    const Vec3 normal1 = triangleNormal(*motion.a1, *motion.b1, *motion.c1);
    const Real area0 = lengthSquared(normal0);  // squared, as the thresholds below
    const Real area1 = lengthSquared(normal1);
    const Real floor0 = kCollapsed * longestEdgeSquared(*motion.a0, *motion.b0, *motion.c0);
    const Real floor1 = kCollapsed * longestEdgeSquared(*motion.a1, *motion.b1, *motion.c1);
    // A collapsed face (its corners on a line, give or take rounding) has no side: its nodes' own
    // contacts handle it.
    if (!(area0 > floor0 * floor0) || !(area1 > floor1 * floor1)) {
      return false;
    }
    motion.n0 = normal0 / std::sqrt(area0);
    motion.n1 = normal1 / std::sqrt(area1);
    motion.turned = dot(motion.n0, motion.n1) < 0;
    motion.onEnd = TriangleProjector(*motion.a1, *motion.b1, *motion.c1);
    return true;
  }

  // A static tool point against a moving soft face.
  // p is model.points[point].
  void toolPoint(Index point, const Vec3& p, const FaceMotion& face) {
    ++counters.triangleTests;
    // Within the skin, a face that touched the tool last step keeps the side it was on: if the
    // soft solver left it slightly pierced, the geometry shows the wrong side. Farther out the
    // geometry decides, so that a face wrapping around a rim over several steps can turn.
    const Real startDistance = dot(face.n0, p - *face.a0);
    int side = std::abs(startDistance) < skin ? memory.faceSide(patch.faceIds[face.face]) : 0;
    if (side == 0 && std::abs(startDistance) > onSurface) {
      side = signOf(startDistance);
    }
    if (side == 0) {
      return;
    }
    const int endSide = face.turned ? -side : side;  // the side's sign, followed through a turn-over
    const Real endDistance = dot(face.n1, p - *face.a1);
    const bool crossed = signOf(endDistance) != endSide;
    if (!crossed && endSide * endDistance >= skin) {
      return;  // clear of the face at the end, and never through it
    }
    Vec3 weights;
    const bool overFace = face.onEnd.project(p, weights) &&
                          weights.x >= -kOverlapTolerance && weights.y >= -kOverlapTolerance &&
                          weights.z >= -kOverlapTolerance;
    Real timeOfImpact = 1;
    bool touching = overFace && !crossed;
    if (crossed) {
      const PointTriangleCcd crossing =
          pointTriangleCcd(p, *face.a0, *face.b0, *face.c0, *face.a1, *face.b1, *face.c1);
      touching = crossing.hit || overFace;
      timeOfImpact = crossing.hit ? crossing.t : 1;
    }
    if (!touching) {
      return;
    }
    ++counters.candidates;
    memory.setFaceSide(patch.faceIds[face.face], side);
    const bool isNode = point < model.nodeCount();
    // The face must stay on its own side of the point: from the point, towards -endSide·n1.
    emit(ContactKind::ToolPoint, patch.faces[face.face].data(), 3, clampedBarycentric(weights), p,
         face.n1 * Real(-endSide), timeOfImpact, isNode ? point : kInvalidIndex,
         isNode ? kInvalidIndex : point - model.nodeCount(), face.face);
  }

  // Whether the soft edge's line ends clear of the tool edge's line by more than the skin, on the
  // side it started on, beyond any doubt from rounding: what edge() returns early for, decided on
  // squares so that the pairs it skips (most of those near a round tool) cost no square root. The
  // margins only leave borderline pairs to edge()'s own reading. w0, w1: the lines' common normals
  // (unnormalised) at the start and the end; fromStart, fromEnd: the soft edge's first node from
  // the tool edge's first point.
  bool clearAtEnd(const Vec3& w0, const Vec3& w1, const Vec3& fromStart, const Vec3& fromEnd) const {
    const Real startDot = dot(w0, fromStart);
    if (!(startDot * startDot > 4 * onSurface * onSurface * lengthSquared(w0))) {
      return false;  // on or near the tool edge's line at the start: no side to read quickly
    }
    const int side = signOf(startDot);
    const int endSide = dot(w0, w1) >= 0 ? side : -side;
    const Real ahead = Real(endSide) * dot(w1, fromEnd);
    return ahead > 0 && ahead * ahead > skin * skin * lengthSquared(w1) * (1 + kSquaresMargin);
  }

  // A static tool edge against a moving soft edge (patch vertices e0, e1).
  void edge(Index toolEdge, Index e0, Index e1) {
    ++counters.triangleTests;
    const Vec3& p0 = model.mesh.vertices[model.featureEdges[toolEdge][0]];
    const Vec3& p1 = model.mesh.vertices[model.featureEdges[toolEdge][1]];
    const Vec3 along = p1 - p0;
    const Vec3 w0 = cross(along, start[e1] - start[e0]);
    const Vec3 w1 = cross(along, end[e1] - end[e0]);
    if (clearAtEnd(w0, w1, start[e0] - p0, end[e0] - p0)) {
      return;
    }
    const Real w0Length = length(w0);
    const Real w1Length = length(w1);
    const Real scale = length(along) * std::max(length(start[e1] - start[e0]), length(end[e1] - end[e0]));
    if (!(w0Length > kOnSurface * scale) || !(w1Length > kOnSurface * scale)) {
      return;  // parallel edges: the point and node tests cover them
    }
    const Real startDistance = dot(w0 / w0Length, start[e0] - p0);
    if (!(std::abs(startDistance) > onSurface)) {
      return;
    }
    const int side = signOf(startDistance);
    const int endSide = dot(w0, w1) >= 0 ? side : -side;
    const Vec3 normal = w1 / w1Length;
    const Real endDistance = dot(normal, end[e0] - p0);
    const bool crossed = signOf(endDistance) != endSide;
    if (!crossed && endSide * endDistance >= skin) {
      return;  // the lines are clear at the end, and the edges never passed each other
    }
    Real u = 0, s = 0;
    closestPointsOfSegments(p0, p1, end[e0], end[e1], u, s);
    Real timeOfImpact = 1;
    bool touching = !crossed && u > 0 && u < 1 && s > 0 && s < 1;
    if (crossed) {
      const EdgeEdgeCcd crossing = edgeEdgeCcd(p0, p1, start[e0], start[e1], end[e0], end[e1]);
      if (crossing.hit) {
        touching = true;
        timeOfImpact = crossing.t;
      }
    }
    if (!touching) {
      return;
    }
    ++counters.candidates;
    const Index vertices[2] = {e0, e1};
    emit(ContactKind::Edge, vertices, 2, {1 - s, s, 0}, p0 + along * u, normal * Real(endSide), timeOfImpact,
         kInvalidIndex, toolEdge, kInvalidIndex);
  }
};

}  // namespace

void SideMemory::resize(Index softNodes, Index softFaces) {
  if (m_nodeStamps.size() != softNodes) {
    m_nodePlane.assign(softNodes, kInvalidIndex);
    m_nodeStamps.reset(softNodes);
  }
  if (m_faceStamps.size() != softFaces) {
    m_faceSideSign.assign(softFaces, 0);
    m_faceStamps.reset(softFaces);
  }
}

void detectSwept(const StepContext& step, const SoftPatch& patch, SideMemory& memory, SweptWorkspace& work,
                 DetectionResult& out) {
  THINTOOL_ASSERT(patch.consistent());
  const ToolModel& model = step.model;
  const Pose& previousPose = step.previousPose;
  const Pose& pose = step.pose;
  const Real skin = step.skin;
  std::vector<PatchContact>& outContacts = out.contacts;
  DetectionCounters& outCounters = out.counters;
  out.excludedNodes[0].clear();
  out.excludedNodes[1].clear();
  outContacts.clear();
  outCounters = DetectionCounters{};
  outCounters.facesGathered = patch.faceCount();
  memory.beginStep();

  const Index vertexCount = patch.vertexCount();
  work.m_start.resize(vertexCount);
  work.m_end.resize(vertexCount);
  work.m_valid.resize(vertexCount);
  for (Index v = 0; v < vertexCount; ++v) {
    work.m_valid[v] = isFinite(patch.positions[v]) && isFinite(patch.previousPositions[v]) ? 1 : 0;
    work.m_start[v] = previousPose.applyInverse(patch.previousPositions[v]);
    work.m_end[v] = pose.applyInverse(patch.positions[v]);
  }
  const Real size = length(model.bounds.extent());
  // The projection onto a face admits barycentric coordinates down to -kOverlapTolerance.
  const Real tolerance = kOverlapTolerance * size;
  // The arc only where detection follows it: reading the chord, nothing of it is needed.
  int arcSamples = 1;
  if (step.maxTurnPerSample > 0) {
    const PieceMotion arc = step.motion();
    work.m_arc.resize(PieceMotion::kMostSamples + 1);
    arc.samplePoses(work.m_arc.data());
    arcSamples = arc.samples();
  }
  Sweep sweep{model,        pose,       patch,              skin,       kOnSurface * size, tolerance, memory,
              work.m_start, work.m_end, work.m_arc.data(), arcSamples, outContacts,       outCounters};

  // Soft nodes against the solid.
  const Aabb grownTool = model.bounds.expanded(skin);
  const bool haveChecked = patch.checkedPositions.size() == vertexCount;
  for (Index v = 0; v < vertexCount; ++v) {
    if (!work.m_valid[v] || !(patch.inverseMasses[v] > 0)) {
      continue;
    }
    Aabb path = Aabb::fromPoints(work.m_start[v], work.m_end[v]);
    Vec3 checked;
    if (haveChecked && isFinite(patch.checkedPositions[v])) {
      checked = previousPose.applyInverse(patch.checkedPositions[v]);
      path.include(checked);
    }
    if (path.overlaps(grownTool)) {
      sweep.softNode(v, haveChecked ? &checked : nullptr);
    }
  }

  // Tool points against soft faces, and tool edges against the faces' edges.
  for (Index f = 0; f < patch.faceCount(); ++f) {
    const auto& corners = patch.faces[f];
    if (!work.m_valid[corners[0]] || !work.m_valid[corners[1]] || !work.m_valid[corners[2]]) {
      ++outCounters.skippedFaces;
      continue;
    }
    const Aabb motionBox = boxOf({work.m_start[corners[0]], work.m_start[corners[1]], work.m_start[corners[2]],
                                  work.m_end[corners[0]], work.m_end[corners[1]], work.m_end[corners[2]]});
    const Aabb swept = motionBox.expanded(skin);
    if (!swept.overlaps(model.bounds)) {
      continue;
    }
    Sweep::FaceMotion motion;
    if (!sweep.faceMotion(f, motion)) {
      ++outCounters.skippedFaces;  // zero area at the start or the end: no side to keep
    } else {
      // A tool point touches the face when the moving face passes over it, which keeps it inside
      // the box of the face's corners, or when it ends within the skin of the face and over it,
      // which puts it at most skin·|n| from that box along each axis. Growing the box by the skin
      // along the normals only, not in every direction, keeps the candidates to about those the
      // face covers.
      const Vec3 reach{skin * std::max(std::abs(motion.n0.x), std::abs(motion.n1.x)),
                       skin * std::max(std::abs(motion.n0.y), std::abs(motion.n1.y)),
                       skin * std::max(std::abs(motion.n0.z), std::abs(motion.n1.z))};
      const Aabb covered{motionBox.min - reach - Vec3{tolerance, tolerance, tolerance},
                         motionBox.max + reach + Vec3{tolerance, tolerance, tolerance}};
      model.pointGrid.queryBox(covered, [&](Index point, const Vec3& p) {
        ++outCounters.nodesTested;
        sweep.toolPoint(point, p, motion);
      });
    }
    for (Index e = 0; e < model.featureEdges.size(); ++e) {
      if (!swept.overlaps(model.featureEdgeBoxes[e])) {
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        sweep.edge(e, corners[k], corners[(k + 1) % 3]);
      }
    }
  }
  outCounters.colliding = static_cast<Index>(outContacts.size());
}

}  // namespace thintool
