// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

#include <thintool/core/Math.h>

#include <limits>

namespace thintool {

/// Axis-aligned box; the default one is empty (min > max) and grows with include().
struct Aabb {
  Vec3 min{std::numeric_limits<Real>::max(), std::numeric_limits<Real>::max(), std::numeric_limits<Real>::max()};
  Vec3 max{-std::numeric_limits<Real>::max(), -std::numeric_limits<Real>::max(), -std::numeric_limits<Real>::max()};

  static constexpr Aabb fromPoints(const Vec3& a, const Vec3& b) { return {componentMin(a, b), componentMax(a, b)}; }

  void include(const Vec3& p) {
    min = componentMin(min, p);
    max = componentMax(max, p);
  }
  void include(const Aabb& b) {
    min = componentMin(min, b.min);
    max = componentMax(max, b.max);
  }
  constexpr Aabb expanded(Real margin) const {
    return {min - Vec3{margin, margin, margin}, max + Vec3{margin, margin, margin}};
  }
  constexpr bool isEmpty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  constexpr Vec3 center() const { return (min + max) * Real(0.5); }
  constexpr Vec3 extent() const { return max - min; }
  constexpr bool overlaps(const Aabb& b) const {
    return min.x <= b.max.x && max.x >= b.min.x && min.y <= b.max.y && max.y >= b.min.y && min.z <= b.max.z &&
           max.z >= b.min.z;
  }
  constexpr bool contains(const Vec3& p) const {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
  }
};

/// The world box of a box given in a frame placed at pose: the box round its eight corners.
inline Aabb transformedBounds(const Aabb& local, const Pose& pose) {
  Aabb box;
  for (int corner = 0; corner < 8; ++corner) {
    box.include(pose.apply({(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                            (corner & 4) ? local.max.z : local.min.z}));
  }
  return box;
}

/// Precomputed reciprocal of a segment's delta for repeated slab tests against boxes.
struct SegmentSlab {
  Vec3 origin;
  Vec3 inverseDelta;

  explicit SegmentSlab(const Vec3& inOrigin, const Vec3& delta) : origin(inOrigin) {
    // 1/0 = ±inf is intended: the slab test below handles an axis-parallel segment through it.
    for (int axis = 0; axis < 3; ++axis) {
      inverseDelta[axis] = delta[axis] != 0 ? 1 / delta[axis] : std::numeric_limits<Real>::infinity();
    }
  }

  /// Whether origin + t·delta, t in [0, 1], touches the box.
  bool overlaps(const Aabb& box) const {
    Real tEnter = 0;
    Real tExit = 1;
    for (int axis = 0; axis < 3; ++axis) {
      const Real o = origin[axis];
      const Real inv = inverseDelta[axis];
      if (std::isinf(inv)) {
        if (o < box.min[axis] || o > box.max[axis]) {
          return false;
        }
        continue;
      }
      Real t0 = (box.min[axis] - o) * inv;
      Real t1 = (box.max[axis] - o) * inv;
      if (t0 > t1) {
        const Real swap = t0;
        t0 = t1;
        t1 = swap;
      }
      tEnter = t0 > tEnter ? t0 : tEnter;
      tExit = t1 < tExit ? t1 : tExit;
      if (tEnter > tExit) {
        return false;
      }
    }
    return true;
  }
};

}  // namespace thintool
