// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "WorldKind.h"

#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btSoftMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

namespace thintool::scenes {

SoftWorldOfKind::SoftWorldOfKind(WorldKind kind, btDispatcher& dispatcher, btBroadphaseInterface& broadphase,
                                 btCollisionConfiguration& configuration, btSoftBodySolver& softSolver) {
  if (kind == WorldKind::SoftRigid) {
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    auto world = std::make_unique<btSoftRigidDynamicsWorld>(&dispatcher, &broadphase, m_solver.get(), &configuration,
                                                            &softSolver);
    m_softRigid = world.get();
    m_world = std::move(world);
  } else {
    auto solver = std::make_unique<btMultiBodyConstraintSolver>();
    auto world = std::make_unique<btSoftMultiBodyDynamicsWorld>(&dispatcher, &broadphase, solver.get(),
                                                                &configuration, &softSolver);
    m_solver = std::move(solver);
    m_softMultiBody = world.get();
    m_world = std::move(world);
  }
}

SoftWorldOfKind::~SoftWorldOfKind() {
  m_world.reset();  // before its solver
}

btSoftBodyWorldInfo& SoftWorldOfKind::worldInfo() {
  return m_softRigid != nullptr ? m_softRigid->getWorldInfo() : m_softMultiBody->getWorldInfo();
}

void SoftWorldOfKind::addSoftBody(btSoftBody* body) {
  if (m_softRigid != nullptr) {
    m_softRigid->addSoftBody(body);
  } else {
    m_softMultiBody->addSoftBody(body);
  }
}

void SoftWorldOfKind::removeSoftBody(btSoftBody* body) {
  if (m_softRigid != nullptr) {
    m_softRigid->removeSoftBody(body);
  } else {
    m_softMultiBody->removeSoftBody(body);
  }
}

}  // namespace thintool::scenes
