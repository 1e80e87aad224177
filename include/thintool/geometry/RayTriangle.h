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
///
/// intersectSegmentTriangleBlock is the same test on eight triangles at once, stored by coordinate
/// (TriangleBlock), for callers that meet one segment against many triangles. Its loop has no
/// branch, so that the compiler vectorises it; it computes every quantity in the scalar kernel's
/// order and applies the same parallel and tolerance rules, so each lane's hit, t, u and v are
/// those intersectSegmentTriangle returns for that triangle, bit for bit wherever the compiler
/// fuses no multiply-add into either (x86-64 without -mfma; GCC in ISO mode fuses none at all).

#include <thintool/core/Math.h>

#include <limits>

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

/// Up to eight triangles by coordinate: the first corner and the two edges from it, as the scalar
/// kernel forms them. Empty lanes hold NaN, which every test rejects, so the kernel needs no count.
struct TriangleBlock {
  static constexpr int kSize = 8;

  alignas(64) Real v0[3][kSize];  ///< [axis][lane]
  alignas(64) Real e1[3][kSize];  ///< v1 - v0
  alignas(64) Real e2[3][kSize];  ///< v2 - v0
  int count = 0;

  TriangleBlock() { clear(); }

  void clear() {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    for (int axis = 0; axis < 3; ++axis) {
      for (int lane = 0; lane < kSize; ++lane) {
        v0[axis][lane] = nan;
        e1[axis][lane] = nan;
        e2[axis][lane] = nan;
      }
    }
    count = 0;
  }

  /// Puts triangle (a, b, c) in lane `lane`, without changing count.
  void set(int lane, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 edge1 = b - a;
    const Vec3 edge2 = c - a;
    for (int axis = 0; axis < 3; ++axis) {
      v0[axis][lane] = a[axis];
      e1[axis][lane] = edge1[axis];
      e2[axis][lane] = edge2[axis];
    }
  }

  /// Appends a triangle in the next lane; false when the block is full.
  bool push(const Vec3& a, const Vec3& b, const Vec3& c) {
    if (count == kSize) {
      return false;
    }
    set(count++, a, b, c);
    return true;
  }
};

/// A segment against a TriangleBlock: lane k is triangle k's result. Misses, the empty lanes
/// included, have t = u = v = 0, as the scalar kernel's.
struct SegmentTriangleBlockHits {
  alignas(64) Real t[TriangleBlock::kSize];
  alignas(64) Real u[TriangleBlock::kSize];
  alignas(64) Real v[TriangleBlock::kSize];
  unsigned mask = 0;  ///< bit k set when lane k hits

  bool hit(int lane) const { return ((mask >> lane) & 1U) != 0; }
};

/// intersectSegmentTriangle(origin, delta, ...) against every lane of block.
inline SegmentTriangleBlockHits intersectSegmentTriangleBlock(const Vec3& origin, const Vec3& delta,
                                                              const TriangleBlock& block) {
  constexpr int kLanes = TriangleBlock::kSize;
  constexpr Real kParallelCosineSquared = kParallelCosine * kParallelCosine;
  // Locals, and results written to a local object, so that no store in the loop may alias a load:
  // at -O2, GCC vectorises only loops that need no run-time alias check.
  const Real ox = origin.x, oy = origin.y, oz = origin.z;
  const Real dx = delta.x, dy = delta.y, dz = delta.z;
  const Real deltaSquared = dx * dx + dy * dy + dz * dz;
  SegmentTriangleBlockHits out;
  // Hit flags as doubles: SSE2 has no 64-bit integer compare, so a flag of a double's width must
  // be a double for the loop to vectorise without -msse4.2.
  alignas(64) Real flags[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    const Real e1x = block.e1[0][k], e1y = block.e1[1][k], e1z = block.e1[2][k];
    const Real e2x = block.e2[0][k], e2y = block.e2[1][k], e2z = block.e2[2][k];

    // p = delta × e2, det = e1·p, and |e1 × e2|² by the Lagrange identity, as the scalar kernel.
    const Real px = dy * e2z - dz * e2y;
    const Real py = dz * e2x - dx * e2z;
    const Real pz = dx * e2y - dy * e2x;
    const Real det = e1x * px + e1y * py + e1z * pz;
    const Real e1e2 = e1x * e2x + e1y * e2y + e1z * e2z;
    const Real e1Squared = e1x * e1x + e1y * e1y + e1z * e1z;
    const Real e2Squared = e2x * e2x + e2y * e2y + e2z * e2z;
    const Real areaSquared4 = e1Squared * e2Squared - e1e2 * e1e2;
    const Real parallelBound = kParallelCosineSquared * deltaSquared * areaSquared4;
    // Lanes that fail the parallel test divide by a zero or tiny det here; their results are
    // discarded below, and IEEE division does not trap.
    const Real invDet = 1 / det;

    const Real sx = ox - block.v0[0][k];
    const Real sy = oy - block.v0[1][k];
    const Real sz = oz - block.v0[2][k];
    const Real u = (sx * px + sy * py + sz * pz) * invDet;
    const Real qx = sy * e1z - sz * e1y;
    const Real qy = sz * e1x - sx * e1z;
    const Real qz = sx * e1y - sy * e1x;
    const Real v = (dx * qx + dy * qy + dz * qz) * invDet;
    const Real t = (e2x * qx + e2y * qy + e2z * qz) * invDet;

    // Acceptance tests, so that NaN anywhere is a miss; & rather than && keeps the loop branch-free.
    const bool hit = (det * det > parallelBound) & (u >= -kBarycentricTolerance) &
                     (u <= 1 + kBarycentricTolerance) & (v >= -kBarycentricTolerance) &
                     (u + v <= 1 + kBarycentricTolerance) & (t >= 0) & (t <= 1);
    out.t[k] = hit ? t : 0;
    out.u[k] = hit ? u : 0;
    out.v[k] = hit ? v : 0;
    flags[k] = hit ? 1 : 0;
  }
  unsigned mask = 0;
  for (int k = 0; k < kLanes; ++k) {
    mask |= static_cast<unsigned>(flags[k] != 0) << k;
  }
  out.mask = mask;
  return out;
}

/// Unnormalised normal of triangle (v0, v1, v2): counter-clockwise vertices face along it.
constexpr Vec3 triangleNormal(const Vec3& v0, const Vec3& v1, const Vec3& v2) { return cross(v1 - v0, v2 - v0); }

}  // namespace thintool
