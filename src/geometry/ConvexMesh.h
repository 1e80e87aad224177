// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The surface of one convex tool piece, in the piece's own frame, and the checks ThinTool runs on
/// it before building a tool model from it.

#include "geometry/Aabb.h"

#include <thintool/core/Math.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <limits>
#include <vector>

namespace thintool {

/// Closed convex triangle mesh; triangles are counter-clockwise seen from outside.
struct ConvexMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<Index, 3>> triangles;
};

/// Plane n·x = offset with unit n pointing out of the piece.
struct Plane {
  Vec3 normal;
  Real offset = 0;
  Real signedDistance(const Vec3& p) const { return dot(normal, p) - offset; }
};

/// Describes the first problem found, or returns an empty string for a usable mesh: at least a
/// tetrahedron, finite coordinates, indices in range, no zero-area triangle, closed (every edge
/// shared by exactly two triangles in opposite directions), outward winding and convex (no vertex
/// in front of any face's plane by more than 1e-6 of the mesh size).
std::string validateConvexMesh(const ConvexMesh& mesh);

/// Outward face planes of a valid mesh, one per triangle.
std::vector<Plane> facePlanes(const ConvexMesh& mesh);

/// The largest signed distance of p over the planes of a convex solid: positive outside, minus
/// the depth to the nearest face inside. outPlane, when given, receives the plane that has it.
inline Real outsideDistance(const std::vector<Plane>& planes, const Vec3& p, Index* outPlane = nullptr) {
  Real best = -std::numeric_limits<Real>::max();
  for (Index k = 0; k < static_cast<Index>(planes.size()); ++k) {
    const Real distance = planes[k].signedDistance(p);
    if (distance > best) {
      best = distance;
      if (outPlane != nullptr) *outPlane = k;
    }
  }
  return best;
}

Aabb bounds(const ConvexMesh& mesh);

/// The extent of points along an axis: the least and greatest dot(axis, point).
inline void projectedInterval(const Vec3& axis, const Vec3* points, std::size_t count, Real& low, Real& high) {
  low = std::numeric_limits<Real>::max();
  high = -low;
  for (std::size_t k = 0; k < count; ++k) {
    const Real p = dot(axis, points[k]);
    low = std::min(low, p);
    high = std::max(high, p);
  }
}

/// Smallest width of the piece measured across its face normals: exact for boxes and plates, an
/// upper bound of the true minimum width otherwise. ThinTool calls it the tool's thickness.
Real thicknessAcrossFaces(const ConvexMesh& mesh, const std::vector<Plane>& planes);

/// Distance from a point on or inside the piece along direction (unit) until it leaves the piece.
Real exitDistance(const std::vector<Plane>& planes, const Vec3& point, const Vec3& direction);

/// A ConvexMesh of the box with the given half extents, centred on the origin.
ConvexMesh makeBoxMesh(const Vec3& halfExtents);

}  // namespace thintool
