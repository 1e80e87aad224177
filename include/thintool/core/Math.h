// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The small linear-algebra vocabulary of ThinTool's core.
///
/// The core computes in double precision whatever btScalar is: the ray tests decide which side of
/// a 0.02 m plate a soft face lies on, and those decisions must not change with Bullet's build.
/// The Bullet glue converts at the boundary (bullet/Convert.h).

#include <cmath>
#include <cstdint>
#include <limits>

namespace thintool {

using Real = double;

inline constexpr Real kPi = 3.14159265358979323846;

struct Vec3 {
  Real x = 0;
  Real y = 0;
  Real z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(Real inX, Real inY, Real inZ) : x(inX), y(inY), z(inZ) {}

  constexpr Real operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  Real& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(Real s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(Real s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  Vec3& operator*=(Real s) { x *= s; y *= s; z *= s; return *this; }
  constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
  constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }
};

constexpr Vec3 operator*(Real s, const Vec3& v) { return v * s; }
constexpr Real dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr Real lengthSquared(const Vec3& v) { return dot(v, v); }
inline Real length(const Vec3& v) { return std::sqrt(dot(v, v)); }
constexpr Vec3 componentMin(const Vec3& a, const Vec3& b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
constexpr Vec3 componentMax(const Vec3& a, const Vec3& b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
inline bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Unit vector along v, or the zero vector when v is too short to have a direction.
inline Vec3 normalizedOrZero(const Vec3& v) {
  const Real len = length(v);
  return len > std::numeric_limits<Real>::min() * 1e8 ? v / len : Vec3{};
}

/// Row-major 3x3 matrix; here always a rotation.
struct Mat3 {
  Vec3 row[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  constexpr Vec3 operator*(const Vec3& v) const { return {dot(row[0], v), dot(row[1], v), dot(row[2], v)}; }
  constexpr Mat3 transposed() const {
    Mat3 t;
    for (int i = 0; i < 3; ++i) {
      t.row[i] = {row[0][i], row[1][i], row[2][i]};
    }
    return t;
  }
  /// Rᵀ·v without forming Rᵀ.
  constexpr Vec3 transposeTimes(const Vec3& v) const { return row[0] * v.x + row[1] * v.y + row[2] * v.z; }
  Mat3 operator*(const Mat3& o) const {
    const Mat3 ot = o.transposed();
    Mat3 r;
    for (int i = 0; i < 3; ++i) {
      r.row[i] = {dot(row[i], ot.row[0]), dot(row[i], ot.row[1]), dot(row[i], ot.row[2])};
    }
    return r;
  }
};

/// Rotation about a unit axis by angle (radians), Rodrigues' formula.
inline Mat3 rotationAboutAxis(const Vec3& unitAxis, Real angle) {
  const Real c = std::cos(angle);
  const Real s = std::sin(angle);
  const Real k = 1 - c;
  const Vec3& a = unitAxis;
  Mat3 m;
  m.row[0] = {c + a.x * a.x * k, a.x * a.y * k - a.z * s, a.x * a.z * k + a.y * s};
  m.row[1] = {a.y * a.x * k + a.z * s, c + a.y * a.y * k, a.y * a.z * k - a.x * s};
  m.row[2] = {a.z * a.x * k - a.y * s, a.z * a.y * k + a.x * s, c + a.z * a.z * k};
  return m;
}

/// Rigid transform x_world = rotation·x_local + translation.
struct Pose {
  Mat3 rotation;
  Vec3 translation;

  constexpr Vec3 apply(const Vec3& local) const { return rotation * local + translation; }
  constexpr Vec3 applyToDirection(const Vec3& local) const { return rotation * local; }
  constexpr Vec3 applyInverse(const Vec3& world) const { return rotation.transposeTimes(world - translation); }
  constexpr Vec3 applyInverseToDirection(const Vec3& world) const { return rotation.transposeTimes(world); }
  Pose operator*(const Pose& o) const { return {rotation * o.rotation, rotation * o.translation + translation}; }
};

inline bool isFinite(const Pose& p) {
  return isFinite(p.translation) && isFinite(p.rotation.row[0]) && isFinite(p.rotation.row[1]) &&
         isFinite(p.rotation.row[2]);
}

/// Index of a tool sample node, a soft face or a soft node; kInvalidIndex marks "none".
using Index = std::uint32_t;
inline constexpr Index kInvalidIndex = std::numeric_limits<Index>::max();

}  // namespace thintool
