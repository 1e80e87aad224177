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
/// fuses no multiply-add into the scalar kernel (x86-64's baseline has no fused instruction; built
/// with -mfma or for another architecture, the scalar kernel may round differently). It is compiled
/// for several instruction sets and dispatched at run time (BlockKernel).

#include <thintool/core/Math.h>

#include <limits>
#include <vector>

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
/// kernel forms them, and |e1 × e2|², which depends on the triangle alone, formed once here as the
/// scalar kernel forms it. Empty lanes hold NaN, which every test rejects, so the kernel needs no
/// count.
struct TriangleBlock {
  static constexpr int kSize = 8;

  alignas(64) Real v0[3][kSize];         ///< [axis][lane]
  alignas(64) Real e1[3][kSize];         ///< v1 - v0
  alignas(64) Real e2[3][kSize];         ///< v2 - v0
  alignas(64) Real areaSquared4[kSize];  ///< |e1|²·|e2|² - (e1·e2)², by the Lagrange identity
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
    for (int lane = 0; lane < kSize; ++lane) {
      areaSquared4[lane] = nan;
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
    const Real e1e2 = dot(edge1, edge2);
    areaSquared4[lane] = lengthSquared(edge1) * lengthSquared(edge2) - e1e2 * e1e2;
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

/// The instruction sets the block kernel is built for. Debian's packages target generic x86-64
/// (SSE2: two lanes of a double at once); the wider variants are compiled into the same binary
/// and chosen at the first call by what the CPU reports, so the package stays portable.
enum class BlockKernel {
  Portable,  ///< the compiler's baseline for the target, on any CPU
  Avx2,      ///< four lanes a vector; x86-64 only
  Avx512,    ///< all eight lanes in one vector; x86-64 only
};

/// The variants this CPU runs, Portable first and the one the dispatch uses last.
const std::vector<BlockKernel>& availableBlockKernels();

/// The variant's name: "portable", "avx2" or "avx512".
const char* blockKernelName(BlockKernel kernel);

/// intersectSegmentTriangle(origin, delta, ...) against every lane of block, with the widest
/// variant the CPU runs. Every variant computes each quantity in the scalar kernel's order with
/// no fused multiply-add (the file is compiled with -ffp-contract=off), so each lane's hit, t, u
/// and v are those intersectSegmentTriangle returns for that triangle, bit for bit.
SegmentTriangleBlockHits intersectSegmentTriangleBlock(const Vec3& origin, const Vec3& delta,
                                                       const TriangleBlock& block);

/// The same with a chosen variant, for tests and benchmarks; one the CPU does not run (not in
/// availableBlockKernels()) falls back to Portable.
SegmentTriangleBlockHits intersectSegmentTriangleBlock(BlockKernel kernel, const Vec3& origin, const Vec3& delta,
                                                       const TriangleBlock& block);

/// Unnormalised normal of triangle (v0, v1, v2): counter-clockwise vertices face along it.
constexpr Vec3 triangleNormal(const Vec3& v0, const Vec3& v1, const Vec3& v2) { return cross(v1 - v0, v2 - v0); }

}  // namespace thintool
