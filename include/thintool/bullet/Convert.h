// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Conversions between Bullet's types and the core's. The core is double precision whatever
/// btScalar is, so the same core serves Bullet's float and float64 builds.

#include <thintool/core/Math.h>

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

namespace thintool {

inline Vec3 toVec3(const btVector3& v) { return {Real(v.x()), Real(v.y()), Real(v.z())}; }

inline btVector3 toBt(const Vec3& v) { return {btScalar(v.x), btScalar(v.y), btScalar(v.z)}; }

inline Pose toPose(const btTransform& t) {
  Pose pose;
  for (int i = 0; i < 3; ++i) {
    pose.rotation.row[i] = toVec3(t.getBasis()[i]);
  }
  pose.translation = toVec3(t.getOrigin());
  return pose;
}

inline btTransform toTransform(const Pose& pose) {
  btMatrix3x3 basis;
  for (int i = 0; i < 3; ++i) {
    basis[i] = toBt(pose.rotation.row[i]);
  }
  return btTransform(basis, toBt(pose.translation));
}

}  // namespace thintool
