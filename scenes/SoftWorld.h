// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A btSoftRigidDynamicsWorld on ThinTool's collision configuration and soft-body solver, with the parts Bullet wants
/// kept alive beside it, for scenes and tests that build their own bodies. Gravity is set on the
/// world and on its soft-body world info alike (Bullet keeps the two apart).

#include <thintool/thintool.h>

#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

namespace thintool::scenes {

struct SoftWorld {
  CollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  SoftBodySolver softSolver{configuration};
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration, &softSolver};

  explicit SoftWorld(const btVector3& gravity = btVector3(0, -10, 0)) {
    world.setGravity(gravity);
    world.getWorldInfo().m_gravity = gravity;
  }
};

}  // namespace thintool::scenes
