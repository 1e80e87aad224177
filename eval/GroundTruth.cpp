// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "GroundTruth.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace thintool::eval {

namespace {

double distanceSquaredToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double abLengthSquared = lengthSquared(ab);
  double t = abLengthSquared > 0 ? dot(p - a, ab) / abLengthSquared : 0;
  t = std::clamp(t, 0.0, 1.0);
  return lengthSquared(p - (a + ab * t));
}

int sideOf(double coordinate) { return coordinate >= 0 ? 1 : -1; }

}  // namespace

ConvexSolid ConvexSolid::box(const Vec3& h) {
  ConvexSolid solid;
  for (int i = 0; i < 8; ++i) {
    solid.vertices.push_back({(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  }
  // Two triangles per face; SolidDistance orients the normals itself, so winding is not relied on.
  solid.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return solid;
}

double distanceSquaredToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = cross(b - a, c - a);
  const double normalLengthSquared = lengthSquared(normal);
  if (normalLengthSquared > 0) {
    const double height = dot(p - a, normal);
    const Vec3 foot = p - normal * (height / normalLengthSquared);
    // The foot of the perpendicular inside the triangle: the plane distance is the distance.
    if (dot(cross(b - a, foot - a), normal) >= 0 && dot(cross(c - b, foot - b), normal) >= 0 &&
        dot(cross(a - c, foot - c), normal) >= 0) {
      return height * height / normalLengthSquared;
    }
  }
  return std::min({distanceSquaredToSegment(p, a, b), distanceSquaredToSegment(p, b, c),
                   distanceSquaredToSegment(p, c, a)});
}

double windingNumber(const Vec3& p, const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
  // Each triangle's signed solid angle seen from p (Van Oosterom and Strackee 1983).
  double solidAngle = 0;
  for (const Triangle& t : triangles) {
    const Vec3 a = vertices[t[0]] - p;
    const Vec3 b = vertices[t[1]] - p;
    const Vec3 c = vertices[t[2]] - p;
    const double la = length(a);
    const double lb = length(b);
    const double lc = length(c);
    const double numerator = dot(a, cross(b, c));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    solidAngle += 2 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4 * kPi);
}

SolidDistance::SolidDistance(ConvexSolid solid) : m_solid(std::move(solid)) {
  const std::vector<Vec3>& vertices = m_solid.vertices;
  if (vertices.size() < 4 || m_solid.triangles.size() < 4) {
    throw Error("ground truth: a tool piece needs at least 4 vertices and 4 triangles");
  }
  Vec3 low = vertices[0];
  Vec3 high = vertices[0];
  Vec3 centroid;
  for (const Vec3& v : vertices) {
    if (!isFinite(v)) throw Error("ground truth: a tool piece has a non-finite vertex");
    low = componentMin(low, v);
    high = componentMax(high, v);
    centroid += v;
  }
  centroid = centroid / double(vertices.size());
  m_centre = (low + high) * 0.5;
  m_halfExtents = (high - low) * 0.5;
  m_thinAxis = 0;
  for (int axis = 1; axis < 3; ++axis) {
    if (m_halfExtents[axis] < m_halfExtents[m_thinAxis]) m_thinAxis = axis;
  }
  for (const Vec3& v : vertices) m_radius = std::max(m_radius, length(v - m_centre));

  const double size = length(high - low);
  const double tolerance = 1e-9 * size;
  for (const Triangle& t : m_solid.triangles) {
    for (int corner : t) {
      if (corner < 0 || corner >= int(vertices.size())) throw Error("ground truth: a triangle index is out of range");
    }
    Vec3 normal = cross(vertices[t[1]] - vertices[t[0]], vertices[t[2]] - vertices[t[0]]);
    const double normalLength = length(normal);
    if (!(normalLength > 1e-12 * size * size)) throw Error("ground truth: a tool piece has a zero-area triangle");
    normal = normal / normalLength;
    double offset = dot(normal, vertices[t[0]]);
    // The vertex centroid lies inside a convex solid: the outward normal points away from it.
    if (dot(normal, centroid) > offset) {
      normal = -normal;
      offset = -offset;
    }
    m_normals.push_back(normal);
    m_offsets.push_back(offset);
  }
  for (std::size_t f = 0; f < m_normals.size(); ++f) {
    if (!(dot(m_normals[f], centroid) - m_offsets[f] < -tolerance)) {
      throw Error("ground truth: a tool piece is flat");
    }
    for (const Vec3& v : vertices) {
      if (dot(m_normals[f], v) - m_offsets[f] > 1e-6 * size) throw Error("ground truth: a tool piece is not convex");
    }
  }
}

double SolidDistance::signedDistance(const Vec3& p) const {
  double farthestPlane = -1e300;
  for (std::size_t f = 0; f < m_normals.size(); ++f) {
    farthestPlane = std::max(farthestPlane, dot(m_normals[f], p) - m_offsets[f]);
  }
  if (farthestPlane <= 0) {
    return farthestPlane;
  }
  double nearest = 1e300;
  for (const Triangle& t : m_solid.triangles) {
    nearest = std::min(nearest, distanceSquaredToTriangle(p, m_solid.vertices[t[0]], m_solid.vertices[t[1]],
                                                          m_solid.vertices[t[2]]));
  }
  return std::sqrt(nearest);
}

GroundTruth::GroundTruth(std::vector<GroundTruthPiece> pieces, bool closedSurface)
    : m_pieces(std::move(pieces)), m_closedSurface(closedSurface) {}

std::vector<Pose> GroundTruth::piecePoses(const std::vector<Pose>& toolPoses) const {
  std::vector<Pose> poses;
  poses.reserve(m_pieces.size());
  for (const GroundTruthPiece& piece : m_pieces) {
    if (piece.tool < 0 || piece.tool >= int(toolPoses.size())) throw Error("ground truth: a piece names a missing tool");
    poses.push_back(toolPoses[piece.tool] * piece.inTool);
  }
  return poses;
}

void GroundTruth::start(const std::vector<Pose>& toolPoses, const std::vector<Vec3>& nodes,
                        const std::vector<Triangle>& /*faces*/) {
  m_previousPoses = piecePoses(toolPoses);
  m_previousNodes = nodes;
  m_crossedPiece.assign(nodes.size(), -1);
  m_sideBeforeCrossing.assign(nodes.size(), 0);
  m_step = {};
  m_run = {};
  m_sumSquared = 0;
  m_samples = 0;
}

void GroundTruth::measurePenetration(const Vec3& world, const std::vector<Pose>& poses) {
  double depth = 0;
  for (std::size_t k = 0; k < m_pieces.size(); ++k) {
    const SolidDistance& solid = m_pieces[k].solid;
    const Vec3 local = poses[k].applyInverse(world);
    if (lengthSquared(local - solid.centre()) > solid.boundingRadius() * solid.boundingRadius()) continue;
    depth = std::max(depth, -solid.signedDistance(local));
  }
  if (depth > 0) {
    m_step.maxPenetration = std::max(m_step.maxPenetration, depth);
    m_step.sumSquaredPenetration += depth * depth;
    ++m_step.penetratingSamples;
  }
}

const GroundTruthStep& GroundTruth::update(const std::vector<Pose>& toolPoses, const std::vector<Vec3>& nodes,
                                           const std::vector<Triangle>& faces) {
  if (nodes.size() != m_previousNodes.size()) throw Error("ground truth: the soft body's node count changed");
  const std::vector<Pose> poses = piecePoses(toolPoses);
  m_step = {};

  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t k = 0; k < m_pieces.size(); ++k) {
      const SolidDistance& solid = m_pieces[k].solid;
      const int axis = solid.thinAxis();
      const Vec3 before = m_previousPoses[k].applyInverse(m_previousNodes[i]) - solid.centre();
      const Vec3 after = poses[k].applyInverse(nodes[i]) - solid.centre();
      if (sideOf(before[axis]) == sideOf(after[axis])) continue;
      const double fraction = before[axis] / (before[axis] - after[axis]);
      Vec3 onMidSurface = before + (after - before) * fraction;
      onMidSurface[axis] = 0;
      if (solid.signedDistance(onMidSurface + solid.centre()) > 0) continue;  // passed beside the piece
      if (m_crossedPiece[i] < 0) {
        ++m_run.crossedNodes;
        m_crossedPiece[i] = int(k);
        m_sideBeforeCrossing[i] = static_cast<signed char>(sideOf(before[axis]));
      }
      ++m_step.crossings;
    }
  }

  for (const Vec3& node : nodes) measurePenetration(node, poses);
  for (const Triangle& f : faces) measurePenetration((nodes[f[0]] + nodes[f[1]] + nodes[f[2]]) / 3.0, poses);

  if (m_closedSurface) {
    for (std::size_t k = 0; k < m_pieces.size() && !m_step.toolInside; ++k) {
      const Vec3 centre = poses[k].apply(m_pieces[k].solid.centre());
      m_step.toolInside = std::abs(windingNumber(centre, nodes, faces)) > 0.5;
    }
  }

  ++m_run.steps;
  m_run.toolInsideSteps += m_step.toolInside ? 1 : 0;
  m_run.endsInside = m_step.toolInside;
  m_run.maxPenetration = std::max(m_run.maxPenetration, m_step.maxPenetration);
  m_sumSquared += m_step.sumSquaredPenetration;
  m_samples += m_step.penetratingSamples;
  m_previousPoses = poses;
  m_previousNodes = nodes;
  return m_step;
}

GroundTruthRun GroundTruth::run() const {
  GroundTruthRun run = m_run;
  run.rmsPenetration = m_samples > 0 ? std::sqrt(m_sumSquared / double(m_samples)) : 0;
  run.stillCrossed = 0;
  for (std::size_t i = 0; i < m_previousNodes.size(); ++i) {
    const int k = m_crossedPiece[i];
    if (k < 0) continue;
    const SolidDistance& solid = m_pieces[k].solid;
    const int axis = solid.thinAxis();
    Vec3 local = m_previousPoses[k].applyInverse(m_previousNodes[i]) - solid.centre();
    if (sideOf(local[axis]) == m_sideBeforeCrossing[i]) continue;
    local[axis] = 0;
    if (solid.signedDistance(local + solid.centre()) <= 0) ++run.stillCrossed;
  }
  return run;
}

}  // namespace thintool::eval
