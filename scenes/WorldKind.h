// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

namespace thintool::scenes {

/// The Bullet world a scene is built in.
enum class WorldKind {
  SoftRigid,      ///< btSoftRigidDynamicsWorld, with btSequentialImpulseConstraintSolver
  SoftMultiBody,  ///< btSoftMultiBodyDynamicsWorld, with btMultiBodyConstraintSolver (PyBullet's soft world)
};

}  // namespace thintool::scenes
