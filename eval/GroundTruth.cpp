// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "GroundTruth.h"

#include "geometry/SolidAngle.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

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

// How far inside the piece's rim a point of its mid-surface lies (m, in the piece's frame): its
// depth below the faces that bound the piece across the mid-surface, those turned more than 60°
// from the thin axis (a plate's sides). Infinite for a piece without such faces.
double depthInsideRim(const SolidDistance& solid, const Vec3& local) {
  constexpr double kAcrossMidSurface = 0.5;  // |cos| of the angle between a rim face's normal and the thin axis
  double depth = std::numeric_limits<double>::infinity();
  const std::vector<Vec3>& normals = solid.faceNormals();
  for (std::size_t f = 0; f < normals.size(); ++f) {
    if (std::abs(normals[f][solid.thinAxis()]) >= kAcrossMidSurface) continue;
    depth = std::min(depth, solid.faceOffsets()[f] - dot(normals[f], local));
  }
  return depth;
}

// A node's passage through a piece's mid-surface between two poses, in the piece's frame: 0 when
// it stays on one side or passes beside the piece, else its side (±1) before. A node that crosses
// the mid-surface no deeper than tolerance inside the piece's rim slid along the rim, as a face
// that reaches no deeper than tolerance pierces nothing: it passed beside. Near a blade's edge,
// where the broad faces meet, the whole piece is thinner than the tolerance, and any passage there
// still counts.
int crossingSide(const SolidDistance& solid, const Pose& poseBefore, const Vec3& nodeBefore, const Pose& poseAfter,
                 const Vec3& nodeAfter, double tolerance) {
  const int axis = solid.thinAxis();
  const Vec3 before = poseBefore.applyInverse(nodeBefore) - solid.centre();
  const Vec3 after = poseAfter.applyInverse(nodeAfter) - solid.centre();
  if (sideOf(before[axis]) == sideOf(after[axis])) return 0;
  const double fraction = before[axis] / (before[axis] - after[axis]);
  Vec3 onMidSurface = before + (after - before) * fraction;
  onMidSurface[axis] = 0;
  const Vec3 local = onMidSurface + solid.centre();
  if (solid.signedDistance(local) > 0) return 0;  // passed beside the piece
  if (depthInsideRim(solid, local) <= tolerance) return 0;  // slid along its rim
  return sideOf(before[axis]);
}

// Unit quaternions, only to interpolate a rotation along its arc: Math.h keeps rotations as
// matrices, whose linear blend is no rotation.
struct Quaternion {
  double w = 1;
  double x = 0;
  double y = 0;
  double z = 0;
};

// Shepperd's method: from the largest of the four squared components, so that no division is by
// a small number, whatever the angle (180° included).
Quaternion quaternionOf(const Mat3& m) {
  const double m00 = m.row[0].x, m11 = m.row[1].y, m22 = m.row[2].z;
  const double trace = m00 + m11 + m22;
  Quaternion q;
  if (trace >= m00 && trace >= m11 && trace >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 + trace));
    q = {s / 4, (m.row[2].y - m.row[1].z) / s, (m.row[0].z - m.row[2].x) / s, (m.row[1].x - m.row[0].y) / s};
  } else if (m00 >= m11 && m00 >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 + m00 - m11 - m22));
    q = {(m.row[2].y - m.row[1].z) / s, s / 4, (m.row[0].y + m.row[1].x) / s, (m.row[0].z + m.row[2].x) / s};
  } else if (m11 >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 - m00 + m11 - m22));
    q = {(m.row[0].z - m.row[2].x) / s, (m.row[0].y + m.row[1].x) / s, s / 4, (m.row[1].z + m.row[2].y) / s};
  } else {
    const double s = 2 * std::sqrt(std::max(0.0, 1 - m00 - m11 + m22));
    q = {(m.row[1].x - m.row[0].y) / s, (m.row[0].z + m.row[2].x) / s, (m.row[1].z + m.row[2].y) / s, s / 4};
  }
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / norm, q.x / norm, q.y / norm, q.z / norm};
}

Mat3 matrixOf(const Quaternion& q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  Mat3 m;
  m.row[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
  m.row[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
  m.row[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
  return m;
}

double quaternionDot(const Quaternion& a, const Quaternion& b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }

// The angle (radians) of the rotation taking a to b, the shorter way.
double turnBetween(const Quaternion& a, const Quaternion& b) {
  return 2 * std::acos(std::min(1.0, std::abs(quaternionDot(a, b))));
}

// The rotation a fraction s of the way from a to b along the shorter arc.
Quaternion slerp(const Quaternion& a, Quaternion b, double s) {
  double cosine = quaternionDot(a, b);
  if (cosine < 0) {
    b = {-b.w, -b.x, -b.y, -b.z};
    cosine = -cosine;
  }
  double wa = 1 - s;
  double wb = s;
  if (cosine < 0.9999) {  // nearer, the sines vanish and the linear blend is as good
    const double angle = std::acos(cosine);
    wa = std::sin((1 - s) * angle) / std::sin(angle);
    wb = std::sin(s * angle) / std::sin(angle);
  }
  Quaternion q{wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z};
  const double norm = std::sqrt(quaternionDot(q, q));
  return {q.w / norm, q.x / norm, q.y / norm, q.z / norm};
}

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

bool surfaceIntersectsItself(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
  if (triangles.size() < 2) return false;
  double edgeSum = 0;
  Vec3 low = vertices[triangles[0][0]];
  Vec3 high = low;
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      edgeSum += length(vertices[t[(k + 1) % 3]] - vertices[t[k]]);
      low = componentMin(low, vertices[t[k]]);
      high = componentMax(high, vertices[t[k]]);
    }
  }
  const double cell = std::max(edgeSum / (3.0 * double(triangles.size())), 1e-9);
  // Each face goes into every cell its box touches, at most kMostCells a side (larger faces in the
  // same coarse cells as their neighbours, which is still exact, only slower).
  constexpr long kMostCells = 1 << 20;
  const auto cellOf = [&](double x, double origin) { return long(std::floor((x - origin) / cell)); };
  std::unordered_map<long long, std::vector<int>> grid;
  const auto key = [](long x, long y, long z) {
    return (static_cast<long long>(x) * 73856093LL) ^ (static_cast<long long>(y) * 19349663LL) ^
           (static_cast<long long>(z) * 83492791LL);
  };
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    Vec3 a = vertices[triangles[f][0]];
    Vec3 b = a;
    for (int k = 1; k < 3; ++k) {
      a = componentMin(a, vertices[triangles[f][k]]);
      b = componentMax(b, vertices[triangles[f][k]]);
    }
    const long x0 = cellOf(a.x, low.x), x1 = std::min(cellOf(b.x, low.x), x0 + kMostCells);
    const long y0 = cellOf(a.y, low.y), y1 = std::min(cellOf(b.y, low.y), y0 + kMostCells);
    const long z0 = cellOf(a.z, low.z), z1 = std::min(cellOf(b.z, low.z), z0 + kMostCells);
    if ((x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1) > 4096) continue;  // a face flung across the scene
    for (long x = x0; x <= x1; ++x)
      for (long y = y0; y <= y1; ++y)
        for (long z = z0; z <= z1; ++z) grid[key(x, y, z)].push_back(int(f));
  }
  const auto edgeThroughFace = [&](const Vec3& p, const Vec3& q, const Triangle& face) {
    const Vec3& a = vertices[face[0]];
    const Vec3& b = vertices[face[1]];
    const Vec3& c = vertices[face[2]];
    const Vec3 normal = cross(b - a, c - a);
    const double dp = dot(normal, p - a);
    const double dq = dot(normal, q - a);
    if ((dp > 0) == (dq > 0) || dp == dq) return false;
    const Vec3 x = p + (q - p) * (dp / (dp - dq));
    return dot(cross(b - a, x - a), normal) > 0 && dot(cross(c - b, x - b), normal) > 0 &&
           dot(cross(a - c, x - c), normal) > 0;
  };
  for (const auto& binned : grid) {
    const std::vector<int>& faces = binned.second;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      for (std::size_t j = 0; j < faces.size(); ++j) {
        if (i == j) continue;
        const Triangle& edgeFace = triangles[std::size_t(faces[i])];
        const Triangle& face = triangles[std::size_t(faces[j])];
        bool sharesNode = false;
        for (int u : edgeFace) {
          for (int v : face) sharesNode = sharesNode || u == v;
        }
        if (sharesNode) continue;
        for (int k = 0; k < 3; ++k) {
          if (edgeThroughFace(vertices[edgeFace[k]], vertices[edgeFace[(k + 1) % 3]], face)) return true;
        }
      }
    }
  }
  return false;
}

double windingNumber(const Vec3& p, const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
  double solidAngle = 0;
  for (const Triangle& t : triangles) {
    solidAngle += triangleSolidAngle(vertices[t[0]] - p, vertices[t[1]] - p, vertices[t[2]] - p);
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

GroundTruth::GroundTruth(std::vector<GroundTruthPiece> pieces, bool closedSurface, double tolerance)
    : m_pieces(std::move(pieces)), m_closedSurface(closedSurface), m_tolerance(tolerance) {
  if (!(tolerance >= 0)) throw Error("ground truth: the piercing tolerance must be 0 m or more");
}

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
                        const std::vector<Triangle>& /*faces*/, std::vector<int> pinned) {
  for (int i : pinned) {
    if (i < 0 || i >= int(nodes.size())) throw Error("ground truth: a pinned node index is out of range");
  }
  m_pinned = std::move(pinned);
  m_previousToolPoses = toolPoses;
  m_previousPoses = piecePoses(toolPoses);
  m_previousNodes = nodes;
  m_crossedPiece.assign(nodes.size(), -1);
  m_sideBeforeCrossing.assign(nodes.size(), 0);
  m_step = {};
  m_run = {};
  m_wrappedByFold = false;
  m_sumSquared = 0;
  m_samples = 0;
}

void GroundTruth::addNodes(const std::vector<Vec3>& nodes) {
  if (nodes.size() < m_previousNodes.size()) throw Error("ground truth: the soft body lost nodes");
  for (std::size_t i = m_previousNodes.size(); i < nodes.size(); ++i) {
    m_previousNodes.push_back(nodes[i]);
    m_crossedPiece.push_back(-1);
    m_sideBeforeCrossing.push_back(0);
  }
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
  m_arcs.resize(m_pieces.size());
  for (std::size_t k = 0; k < m_pieces.size(); ++k) followArc(k, toolPoses, poses, m_arcs[k]);
  m_step.pinnedReached = m_run.pinnedReachedStep > 0 || reachesPinnedNode(poses, nodes);
  if (m_step.pinnedReached && m_run.pinnedReachedStep == 0) m_run.pinnedReachedStep = m_run.steps + 1;

  if (!m_step.pinnedReached) countCrossings(nodes);

  for (const Vec3& node : nodes) measurePenetration(node, poses);
  for (const Triangle& f : faces) measurePenetration((nodes[f[0]] + nodes[f[1]] + nodes[f[2]]) / 3.0, poses);

  for (const Triangle& f : faces) {
    const Vec3& a = nodes[f[0]];
    const Vec3& b = nodes[f[1]];
    const Vec3& c = nodes[f[2]];
    const Vec3 low = componentMin(a, componentMin(b, c));
    const Vec3 high = componentMax(a, componentMax(b, c));
    for (std::size_t k = 0; k < m_pieces.size(); ++k) {
      const SolidDistance& solid = m_pieces[k].solid;
      // The cheap reject: the face's box against the piece's bounding sphere.
      const Vec3 centre = poses[k].apply(solid.centre());
      const Vec3 nearest = componentMax(low, componentMin(high, centre));
      if (lengthSquared(nearest - centre) > solid.boundingRadius() * solid.boundingRadius()) continue;
      if (pierces(a, b, c, k, poses[k])) {
        ++m_step.piercedFaces;
        break;
      }
    }
  }

  if (m_closedSurface) {
    for (std::size_t k = 0; k < m_pieces.size() && !m_step.toolInside; ++k) {
      const Vec3 centre = poses[k].apply(m_pieces[k].solid.centre());
      m_step.toolInside = std::abs(windingNumber(centre, nodes, faces)) > 0.5;
    }
    if (m_step.toolInside && (m_wrappedByFold || surfaceIntersectsItself(nodes, faces))) {
      m_step.toolInside = false;
      m_step.selfIntersecting = true;
    }
    m_wrappedByFold = m_step.selfIntersecting;
  }

  ++m_run.steps;
  m_previousToolPoses = toolPoses;
  m_previousPoses = poses;
  m_previousNodes = nodes;
  if (m_step.pinnedReached) {
    ++m_run.unjudgedSteps;
    return m_step;
  }
  m_run.toolInsideSteps += m_step.toolInside ? 1 : 0;
  m_run.selfIntersectingSteps += m_step.selfIntersecting ? 1 : 0;
  m_run.endsInside = m_step.toolInside;
  m_run.maxPenetration = std::max(m_run.maxPenetration, m_step.maxPenetration);
  m_run.piercedSteps += m_step.piercedFaces > 0 ? 1 : 0;
  m_run.maxPiercedFaces = std::max(m_run.maxPiercedFaces, m_step.piercedFaces);
  m_sumSquared += m_step.sumSquaredPenetration;
  m_samples += m_step.penetratingSamples;
  return m_step;
}

// The piece's poses at the ends of the sub-intervals its turn between two steps is followed in:
// the tool's pose interpolated, then the piece placed on it, so that a piece offset from the tool's
// origin (a jaw) swings round that origin as the body does. Two poses for a step without a turn.
void GroundTruth::followArc(std::size_t k, const std::vector<Pose>& toolPoses, const std::vector<Pose>& poses,
                            std::vector<Pose>& arc) const {
  const GroundTruthPiece& piece = m_pieces[k];
  const Pose& toolBefore = m_previousToolPoses[piece.tool];
  const Pose& toolAfter = toolPoses[piece.tool];
  const Quaternion turnBefore = quaternionOf(toolBefore.rotation);
  const Quaternion turnAfter = quaternionOf(toolAfter.rotation);
  const int intervals = std::max(1, int(std::ceil(turnBetween(turnBefore, turnAfter) / kMaxTurnPerInterval)));
  arc.assign(std::size_t(intervals) + 1, Pose{});
  arc.front() = m_previousPoses[k];
  arc.back() = poses[k];
  for (int j = 1; j < intervals; ++j) {
    const double s = double(j) / intervals;
    Pose tool;
    tool.rotation = matrixOf(slerp(turnBefore, turnAfter, s));
    tool.translation = toolBefore.translation + (toolAfter.translation - toolBefore.translation) * s;
    arc[std::size_t(j)] = tool * piece.inTool;
  }
}

// Node i's passage through piece k over the step, 0 or its side before. Straight in the piece's
// frame, a node that went round did not cross, whatever the arc says; on a turning piece it
// crossed only when, moving straight in the world, it also passed the piece on its arc.
int GroundTruth::crossingAlongArc(std::size_t k, std::size_t i, const std::vector<Pose>& arc,
                                  const Vec3& nodeAfter) const {
  const SolidDistance& solid = m_pieces[k].solid;
  const Vec3& nodeBefore = m_previousNodes[i];
  const int chord = crossingSide(solid, arc.front(), nodeBefore, arc.back(), nodeAfter, m_tolerance);
  const int intervals = int(arc.size()) - 1;
  if (chord == 0 || intervals == 1) return chord;
  const Vec3 motion = nodeAfter - nodeBefore;
  for (int j = 0; j < intervals; ++j) {
    const Vec3 from = j == 0 ? nodeBefore : nodeBefore + motion * (double(j) / intervals);
    const Vec3 to = j + 1 == intervals ? nodeAfter : nodeBefore + motion * (double(j + 1) / intervals);
    const int side = crossingSide(solid, arc[std::size_t(j)], from, arc[std::size_t(j) + 1], to, m_tolerance);
    if (side != 0) return side;
  }
  return 0;
}

bool GroundTruth::reachesPinnedNode(const std::vector<Pose>& poses, const std::vector<Vec3>& nodes) const {
  for (std::size_t k = 0; k < m_pieces.size(); ++k) {
    if (!m_pieces[k].immovable) continue;
    for (int i : m_pinned) {
      const auto node = std::size_t(i);
      if (m_pieces[k].solid.signedDistance(poses[k].applyInverse(nodes[node])) < 0) return true;
      if (crossingAlongArc(k, node, m_arcs[k], nodes[node]) != 0) return true;
    }
  }
  return false;
}

void GroundTruth::countCrossings(const std::vector<Vec3>& nodes) {
  for (std::size_t k = 0; k < m_pieces.size(); ++k) {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const int side = crossingAlongArc(k, i, m_arcs[k], nodes[i]);
      if (side == 0) continue;
      if (m_crossedPiece[i] < 0) {
        ++m_run.crossedNodes;
        m_crossedPiece[i] = int(k);
        m_sideBeforeCrossing[i] = static_cast<signed char>(side);
      }
      ++m_step.crossings;  // once a step, however often the arc passes the node
    }
  }
}

// Sutherland–Hodgman: the triangle clipped by each face plane moved inward by the tolerance. What
// remains lies deeper than the tolerance inside the piece; nothing remains when no point of the
// triangle does.
bool GroundTruth::pierces(const Vec3& a, const Vec3& b, const Vec3& c, std::size_t piece, const Pose& pose) {
  const SolidDistance& solid = m_pieces[piece].solid;
  m_clipped = {pose.applyInverse(a), pose.applyInverse(b), pose.applyInverse(c)};
  const std::vector<Vec3>& normals = solid.faceNormals();
  const std::vector<double>& offsets = solid.faceOffsets();
  for (std::size_t f = 0; f < normals.size() && !m_clipped.empty(); ++f) {
    const double limit = offsets[f] - m_tolerance;
    m_clipScratch.clear();
    for (std::size_t v = 0; v < m_clipped.size(); ++v) {
      const Vec3& p = m_clipped[v];
      const Vec3& q = m_clipped[(v + 1) % m_clipped.size()];
      const double dp = dot(normals[f], p) - limit;
      const double dq = dot(normals[f], q) - limit;
      if (dp <= 0) m_clipScratch.push_back(p);
      if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) m_clipScratch.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    std::swap(m_clipped, m_clipScratch);
  }
  return !m_clipped.empty();
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
