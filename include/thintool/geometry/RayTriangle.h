// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Segment–triangle intersection, after Möller & Trumbore, "Fast, minimum storage ray-triangle
/// intersection", Journal of Graphics Tools 2(1), 1997 (the paper's eq. 1).
///
/// Deviations from the published kernel:
/// - the ray is a segment origin + t·delta, t in [0, 1], so callers bound the search by the length
///   of delta instead of post-filtering (the paper limits its association rays the same way);
/// - it is two-sided: the caller reads the orientation from the triangle's normal, because
///   ThinTool's filters need to know whether a face was crossed from its inside or its outside;
/// - "parallel" is decided relative to the sizes involved (|det| <= kParallelCosine·|delta|·|e1×e2|),
///   never against an absolute epsilon, so the test behaves the same in millimetres and in metres,
///   and it never divides by zero: a zero-length segment, a zero-area triangle and a segment lying
///   in the triangle's plane all report a miss;
/// - edges and vertices are inclusive within kBarycentricTolerance, so a segment through an edge
///   shared by two triangles hits both; callers that keep the closest hit are unaffected, callers
///   that count hits (parity tests) must not use this kernel.

#include <thintool/core/Math.h>

namespace thintool {

/// Barycentric slack on the edges: a hit with u, v >= -1e-9 and u + v <= 1 + 1e-9 counts. In a
/// 0.45 m soft face this widens the triangle by under a nanometre.
inline constexpr Real kBarycentricTolerance = 1e-9;

/// Cosine between the segment and the triangle's plane under which the two count as parallel.
inline constexpr Real kParallelCosine = 1e-12;

struct SegmentTriangleHit {
  bool hit = false;
  Real t = 0;  ///< fraction along delta, in [0, 1]
  Real u = 0;  ///< barycentric weight of v1
  Real v = 0;  ///< barycentric weight of v2 (v0 gets 1 - u - v)
};

/// Intersects the segment origin + t·delta, t in [0, 1], with triangle (v0, v1, v2), either side.
/// A segment that starts or ends exactly on the triangle hits at t = 0 or t = 1.
inline SegmentTriangleHit intersectSegmentTriangle(const Vec3& origin, const Vec3& delta, const Vec3& v0,
                                                   const Vec3& v1, const Vec3& v2) {
  SegmentTriangleHit result;
  const Vec3 e1 = v1 - v0;
  const Vec3 e2 = v2 - v0;

  // Determinant: det = e1·(delta × e2) = -delta·(e1 × e2).
  const Vec3 p = cross(delta, e2);
  const Real det = dot(e1, p);

  // |e1 × e2|² from the Lagrange identity avoids a second cross product.
  const Real e1e2 = dot(e1, e2);
  const Real areaSquared4 = lengthSquared(e1) * lengthSquared(e2) - e1e2 * e1e2;
  const Real parallelBound = kParallelCosine * kParallelCosine * lengthSquared(delta) * areaSquared4;
  if (!(det * det > parallelBound)) {  // also rejects NaN input
    return result;
  }
  const Real invDet = 1 / det;

  // Edge tests.
  const Vec3 s = origin - v0;
  const Real u = dot(s, p) * invDet;
  // Written as negated acceptance tests so that a NaN coordinate is a miss.
  if (!(u >= -kBarycentricTolerance && u <= 1 + kBarycentricTolerance)) {
    return result;
  }
  const Vec3 q = cross(s, e1);
  const Real v = dot(delta, q) * invDet;
  if (!(v >= -kBarycentricTolerance && u + v <= 1 + kBarycentricTolerance)) {
    return result;
  }

  // Depth test along the segment.
  const Real t = dot(e2, q) * invDet;
  if (!(t >= 0 && t <= 1)) {
    return result;
  }
  result.hit = true;
  result.t = t;
  result.u = u;
  result.v = v;
  return result;
}

/// Unnormalised normal of triangle (v0, v1, v2): counter-clockwise vertices face along it.
constexpr Vec3 triangleNormal(const Vec3& v0, const Vec3& v1, const Vec3& v2) { return cross(v1 - v0, v2 - v0); }

}  // namespace thintool
