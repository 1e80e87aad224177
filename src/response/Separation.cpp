// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/response/Separation.h>

#include <thintool/geometry/Ccd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace thintool {

namespace {

// A path that leaves the piece through a face whose normal is turned more than 60° from the one it
// entered by went through the piece, not round a corner of it.
constexpr Real kTurnedAway = Real(0.5);
// Samples of the arc: a turn of 180° at 5° a sample needs 36; the cap only guards settings.
constexpr int kMostSamples = 64;
// A point counts as over a triangle (in its prism) within this fraction of the triangle's size.
constexpr Real kPrismSlack = 1e-9;

// The rotation R with R = rotationAboutAxis(axis, angle), angle in [0, π].
void axisAngleOf(const Mat3& r, Vec3& outAxis, Real& outAngle) {
  const Real trace = r.row[0].x + r.row[1].y + r.row[2].z;
  const Vec3 skew{r.row[2].y - r.row[1].z, r.row[0].z - r.row[2].x, r.row[1].x - r.row[0].y};
  const Real skewLength = length(skew);
  // |skew| = 2 sin θ and trace − 1 = 2 cos θ: atan2 keeps full precision near 0 and π, where
  // acos of the cosine alone loses half the digits.
  outAngle = std::atan2(skewLength, trace - 1);
  if (outAngle < Real(1e-12)) {
    outAxis = {1, 0, 0};
    outAngle = 0;
  } else if (skewLength > Real(1e-6)) {
    outAxis = skew / skewLength;
  } else {
    // A half turn: R = 2aaᵀ − I, so the axis comes from the column of the largest diagonal.
    int i = 0;
    for (int k = 1; k < 3; ++k) {
      if (r.row[k][k] > r.row[i][i]) i = k;
    }
    Vec3 axis;
    axis[i] = std::sqrt(std::max(Real(0), (r.row[i][i] + 1) / 2));
    for (int k = 0; k < 3; ++k) {
      if (k != i) axis[k] = (r.row[i][k] + r.row[k][i]) / (4 * axis[i]);
    }
    outAxis = normalizedOrZero(axis);
  }
}

struct NodeVerdict {
  bool fix = false;
  Index plane = kInvalidIndex;  // the face the node goes back in front of
};

// Follows a node's path through the piece's frame along the arc (see the file comment of
// Separation.h) and says whether, and through which face, it must go back out.
NodeVerdict judgeNode(const ToolModel& piece, const PieceMotion& motion, const Pose* poses, const Vec3& start,
                      const Vec3& end, Real clearance, Vec3& outEndLocal) {
  const std::vector<Plane>& planes = piece.planes;
  Vec3 previous = motion.start().applyInverse(start);
  Index entered = kInvalidIndex;
  Index carriedFrom = kInvalidIndex;
  const int samples = motion.samples();
  for (int k = 1; k <= samples; ++k) {
    const Real t = Real(k) / Real(samples);
    const Vec3 current = poses[k].applyInverse(k == samples ? end : start + (end - start) * t);
    const ClipResult clip = clipSegmentConvex(planes, 0, previous, current);
    if (clip.hit) {
      if (clip.enterPlane != kInvalidIndex) entered = clip.enterPlane;
      if (clip.leavePlane != kInvalidIndex && entered != kInvalidIndex &&
          dot(planes[entered].normal, planes[clip.leavePlane].normal) < kTurnedAway) {
        carriedFrom = entered;
      }
    }
    previous = current;
  }
  outEndLocal = previous;
  Index nearest = 0;
  if (outsideDistance(planes, previous, &nearest) < 0) {
    return {true, entered != kInvalidIndex ? entered : nearest};
  }
  if (carriedFrom != kInvalidIndex && planes[carriedFrom].signedDistance(previous) < clearance) {
    return {true, carriedFrom};
  }
  return {};
}

// The heights above the plane of triangle (a, b, c) (along its unit normal) of the piece's part
// over the triangle, the triangle's prism: its lowest and highest. False when no part of the
// piece lies over the triangle.
bool heightsOverTriangle(const ToolModel& piece, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal,
                         Real& outLowest, Real& outHighest) {
  outLowest = std::numeric_limits<Real>::max();
  outHighest = -std::numeric_limits<Real>::max();
  const auto include = [&](Real height) {
    outLowest = std::min(outLowest, height);
    outHighest = std::max(outHighest, height);
  };
  const TriangleProjector projector(a, b, c);
  const auto over = [&](const Vec3& p) {
    Vec3 barycentric;
    return projector.project(p, barycentric) && barycentric.x >= -kPrismSlack && barycentric.y >= -kPrismSlack &&
           barycentric.z >= -kPrismSlack;
  };
  // The part over the triangle is a convex solid; its highest and lowest points are among the
  // piece's corners over the triangle, the piece's edges through the prism's sides, and the
  // prism's edges through the piece.
  const std::vector<Vec3>& corners = piece.mesh.vertices;
  for (const Vec3& v : corners) {
    if (over(v)) include(dot(normal, v - a));
  }
  const Vec3 triangle[3] = {a, b, c};
  for (int side = 0; side < 3; ++side) {
    const Vec3& p0 = triangle[side];
    const Vec3& p1 = triangle[(side + 1) % 3];
    const Vec3 sideNormal = cross(normal, p1 - p0);
    for (const auto& edge : piece.featureEdges) {
      const Vec3& u0 = corners[edge[0]];
      const Vec3& u1 = corners[edge[1]];
      const Real s0 = dot(sideNormal, u0 - p0);
      const Real s1 = dot(sideNormal, u1 - p0);
      if ((s0 < 0) == (s1 < 0)) continue;
      const Vec3 crossing = u0 + (u1 - u0) * (s0 / (s0 - s1));
      if (over(crossing)) include(dot(normal, crossing - a));
    }
    // The line p0 + s·normal clipped by the piece's planes.
    Real low = -std::numeric_limits<Real>::max();
    Real high = std::numeric_limits<Real>::max();
    for (const Plane& plane : piece.planes) {
      const Real along = dot(plane.normal, normal);
      const Real distance = plane.signedDistance(p0);
      if (std::abs(along) < Real(1e-12)) {
        if (distance > 0) {
          high = -1;
          low = 1;
          break;
        }
        continue;
      }
      const Real bound = -distance / along;
      if (along > 0) {
        high = std::min(high, bound);
      } else {
        low = std::max(low, bound);
      }
    }
    if (low <= high) {
      const Real base = dot(normal, p0 - a);
      include(base + low);
      include(base + high);
    }
  }
  return outLowest <= outHighest;
}

// Moves a face by `move` (world) at its centroid: each node by its share of inverse mass, the
// smallest mass-weighted change that moves the centroid that far (a plain translation when the
// masses are equal). False when every node is pinned.
bool moveFace(SeparationPatch& patch, const std::array<Index, 3>& face, const Vec3& move) {
  Real weights = 0;
  for (Index v : face) weights += patch.inverseMasses[v];
  if (!(weights > 0)) return false;
  for (Index v : face) {
    patch.positions[v] += move * (3 * patch.inverseMasses[v] / weights);
    patch.moved[v] = 1;
  }
  return true;
}

}  // namespace

PieceMotion::PieceMotion(const Pose& start, const Pose& end, Real maxTurnPerSample) : m_start(start), m_end(end) {
  axisAngleOf(start.rotation.transposed() * end.rotation, m_axis, m_angle);
  const Real samples = std::ceil(m_angle / std::max(maxTurnPerSample, Real(1e-6)));
  m_samples = std::clamp(static_cast<int>(samples), 1, kMostSamples);
}

Pose PieceMotion::at(Real t) const {
  if (t <= 0) return m_start;
  if (t >= 1) return m_end;
  Pose pose;
  pose.rotation = m_start.rotation * rotationAboutAxis(m_axis, m_angle * t);
  pose.translation = m_start.translation + (m_end.translation - m_start.translation) * t;
  return pose;
}

bool triangleMeetsPiece(const ToolModel& piece, const Vec3& a, const Vec3& b, const Vec3& c, Real tolerance) {
  const std::vector<Vec3>& corners = piece.mesh.vertices;
  // Overlap of the two projections on axis (not unit: tolerance is scaled by its length).
  const auto separatedAlong = [&](const Vec3& axis) {
    const Real axisLength = length(axis);
    if (!(axisLength > Real(1e-12))) return false;
    Real pieceLow = std::numeric_limits<Real>::max();
    Real pieceHigh = -pieceLow;
    for (const Vec3& v : corners) {
      const Real p = dot(axis, v);
      pieceLow = std::min(pieceLow, p);
      pieceHigh = std::max(pieceHigh, p);
    }
    const Real pa = dot(axis, a);
    const Real pb = dot(axis, b);
    const Real pc = dot(axis, c);
    const Real triangleLow = std::min({pa, pb, pc});
    const Real triangleHigh = std::max({pa, pb, pc});
    return std::min(pieceHigh - triangleLow, triangleHigh - pieceLow) <= tolerance * axisLength;
  };
  for (const Plane& plane : piece.planes) {
    if (separatedAlong(plane.normal)) return false;
  }
  const Vec3 edges[3] = {b - a, c - b, a - c};
  if (separatedAlong(cross(edges[0], c - a))) return false;
  for (const auto& edge : piece.featureEdges) {
    const Vec3 direction = corners[edge[1]] - corners[edge[0]];
    for (const Vec3& e : edges) {
      if (separatedAlong(cross(direction, e))) return false;
    }
  }
  return true;
}

SeparationCounts separateFromPiece(const ToolModel& piece, const PieceMotion& motion,
                                   const SeparationSettings& settings, SeparationPatch& patch) {
  SeparationCounts counts;
  const Index vertexCount = patch.vertexCount();
  if (vertexCount == 0) return counts;
  const Real clearance = settings.clearance;
  const Pose& end = motion.end();
  const Pose& start = motion.start();
  Pose poses[kMostSamples + 1];
  for (int k = 0; k <= motion.samples(); ++k) poses[k] = motion.at(Real(k) / Real(motion.samples()));
  const Aabb near = piece.bounds.expanded(clearance);

  for (int round = 0; round < std::max(1, settings.maxRounds); ++round) {
    bool changed = false;
    counts.rounds = round + 1;
    for (Index v = 0; v < vertexCount; ++v) {
      if (!(patch.inverseMasses[v] > 0) || (round > 0 && patch.moved[v] != 2)) continue;
      Vec3 local;
      const NodeVerdict verdict =
          judgeNode(piece, motion, poses, patch.startPositions[v], patch.positions[v], clearance, local);
      if (!verdict.fix) continue;
      const Plane& plane = piece.planes[verdict.plane];
      const Vec3 corrected = local + plane.normal * (clearance - plane.signedDistance(local));
      patch.positions[v] = end.apply(corrected);
      patch.moved[v] = 1;
      ++counts.nodesMoved;
      changed = true;
    }
    // Faces whose nodes move in this round are judged again; their nodes are marked 2 so that the
    // next round judges them, and only them.
    for (Index v = 0; v < vertexCount; ++v) {
      if (patch.moved[v] == 2) patch.moved[v] = 1;
    }
    for (const std::array<Index, 3>& face : patch.faces) {
      const Vec3 a = end.applyInverse(patch.positions[face[0]]);
      const Vec3 b = end.applyInverse(patch.positions[face[1]]);
      const Vec3 c = end.applyInverse(patch.positions[face[2]]);
      if (!near.overlaps(Aabb::fromPoints(componentMin(a, componentMin(b, c)), componentMax(a, componentMax(b, c)))) ||
          !triangleMeetsPiece(piece, a, b, c, 0)) {
        continue;
      }
      const Vec3 normal = normalizedOrZero(cross(b - a, c - a));
      Real lowest = 0;
      Real highest = 0;
      if (normal == Vec3{} || !heightsOverTriangle(piece, a, b, c, normal, lowest, highest)) continue;
      // Which side of the face the piece belongs on: where its part over the triangle was at the
      // start of the step, else where most of that part is now.
      int side = highest >= -lowest ? 1 : -1;
      const Vec3 a0 = start.applyInverse(patch.startPositions[face[0]]);
      const Vec3 b0 = start.applyInverse(patch.startPositions[face[1]]);
      const Vec3 c0 = start.applyInverse(patch.startPositions[face[2]]);
      const Vec3 normal0 = normalizedOrZero(cross(b0 - a0, c0 - a0));
      Real lowest0 = 0;
      Real highest0 = 0;
      if (normal0 != Vec3{} && heightsOverTriangle(piece, a0, b0, c0, normal0, lowest0, highest0)) {
        if (lowest0 >= -clearance && highest0 > clearance) side = 1;
        if (highest0 <= clearance && lowest0 < -clearance) side = -1;
      }
      const Real offset = side > 0 ? lowest - clearance : highest + clearance;
      if (side * offset >= 0) continue;  // the piece is already on its side
      if (!moveFace(patch, face, end.applyToDirection(normal * offset))) continue;
      for (Index v : face) patch.moved[v] = 2;
      ++counts.facesMoved;
      changed = true;
    }
    if (!changed) break;
  }

  // What is left, measured as the judge would: half the clearance forgives rounding.
  const Real tolerance = clearance / 2;
  for (Index v = 0; v < vertexCount; ++v) {
    if (patch.moved[v] != 0) patch.moved[v] = 1;
    if (outsideDistance(piece.planes, end.applyInverse(patch.positions[v])) < -tolerance) ++counts.nodesInside;
  }
  for (const std::array<Index, 3>& face : patch.faces) {
    const Vec3 a = end.applyInverse(patch.positions[face[0]]);
    const Vec3 b = end.applyInverse(patch.positions[face[1]]);
    const Vec3 c = end.applyInverse(patch.positions[face[2]]);
    if (triangleMeetsPiece(piece, a, b, c, tolerance)) ++counts.facesPierced;
  }
  return counts;
}

std::string validateSeparationSettings(const SeparationSettings& settings) {
  if (!(settings.clearance > 0) || !std::isfinite(settings.clearance)) {
    return "separation.clearance must be positive and finite (m)";
  }
  if (settings.maxRounds < 1) return "separation.maxRounds must be at least 1";
  if (!(settings.maxTurnPerSample > 0) || !std::isfinite(settings.maxTurnPerSample)) {
    return "separation.maxTurnPerSample must be positive and finite (radians)";
  }
  return {};
}

}  // namespace thintool
