// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "WorldKind.h"

#include <thintool/bullet/DeformableBodySolver.h>
#include <thintool/bullet/SoftBodySolver.h>
#include <thintool/core/Error.h>

#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableMassSpringForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

namespace thintool::scenes {

namespace {
constexpr double kBallNodes = 66;  // CreateEllipsoid's nodes at resolution 63
constexpr double kBallStep = 1.0 / 60;
}  // namespace

double ballSpringFor(const btSoftBody& body) {
  // A spring's frequency goes as sqrt(k / node mass): k scales with the node's mass.
  double mass = 0;
  int free = 0;
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    if (!(body.m_nodes[i].m_im > 0)) continue;
    mass += 1 / double(body.m_nodes[i].m_im);
    ++free;
  }
  if (free == 0) return kDeformableSpring;
  return kDeformableSpring * (mass / free * kBallNodes);
}

double deformableSpringFor(const btSoftBody& body, double stiffness, double step) {
  // The ball's for the body's node mass, and for the step: k scales with 1/step². A quarter of
  // that, for bodies whose nodes have more links than the ball's: at the ball's own share, Bullet's
  // solve of a generated tetrahedral block diverged with no tool near it (seed 16, 633 m/s).
  constexpr double kShare = 0.25;
  if (!(step > 0)) return kDeformableSpring * stiffness;
  return kShare * ballSpringFor(body) * stiffness * (kBallStep / step) * (kBallStep / step);
}

std::unique_ptr<btSoftBodySolver> softSolverFor(WorldKind kind, CollisionConfiguration* thinTool) {
  if (kind == WorldKind::Deformable) {
    if (thinTool != nullptr) return std::make_unique<DeformableBodySolver>(*thinTool);
    return std::make_unique<btDeformableBodySolver>();
  }
  if (thinTool != nullptr) return std::make_unique<SoftBodySolver>(*thinTool);
  return std::make_unique<btDefaultSoftBodySolver>();
}

SoftWorldOfKind::SoftWorldOfKind(WorldKind kind, btDispatcher& dispatcher, btBroadphaseInterface& broadphase,
                                 btCollisionConfiguration& configuration, btSoftBodySolver& softSolver) {
  if (kind == WorldKind::SoftRigid) {
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    auto world = std::make_unique<btSoftRigidDynamicsWorld>(&dispatcher, &broadphase, m_solver.get(), &configuration,
                                                            &softSolver);
    m_softRigid = world.get();
    m_world = std::move(world);
  } else if (kind == WorldKind::SoftMultiBody) {
    auto solver = std::make_unique<btMultiBodyConstraintSolver>();
    auto world = std::make_unique<btSoftMultiBodyDynamicsWorld>(&dispatcher, &broadphase, solver.get(),
                                                                &configuration, &softSolver);
    m_solver = std::move(solver);
    m_softMultiBody = world.get();
    m_world = std::move(world);
  } else {
    auto* deformableSolver = dynamic_cast<btDeformableBodySolver*>(&softSolver);
    if (deformableSolver == nullptr) {
      throw Error("SoftWorldOfKind: the deformable world needs a btDeformableBodySolver (softSolverFor)");
    }
    auto solver = std::make_unique<btDeformableMultiBodyConstraintSolver>();
    solver->setDeformableSolver(deformableSolver);
    auto world = std::make_unique<btDeformableMultiBodyDynamicsWorld>(&dispatcher, &broadphase, solver.get(),
                                                                      &configuration, deformableSolver);
    m_solver = std::move(solver);
    m_deformable = world.get();
    m_world = std::move(world);
  }
}

SoftWorldOfKind::~SoftWorldOfKind() {
  m_world.reset();  // before its solver and the forces
}

btMultiBodyDynamicsWorld* SoftWorldOfKind::multiBody() {
  if (m_softMultiBody != nullptr) return m_softMultiBody;
  return m_deformable;
}

const btAlignedObjectArray<btSoftBody*>& SoftWorldOfKind::softBodies() const {
  if (m_softRigid != nullptr) return m_softRigid->getSoftBodyArray();
  if (m_softMultiBody != nullptr) return m_softMultiBody->getSoftBodyArray();
  return m_deformable->getSoftBodyArray();
}

btSoftBodyWorldInfo& SoftWorldOfKind::worldInfo() {
  if (m_softRigid != nullptr) return m_softRigid->getWorldInfo();
  if (m_softMultiBody != nullptr) return m_softMultiBody->getWorldInfo();
  return m_deformable->getWorldInfo();
}

void SoftWorldOfKind::setGravity(const btVector3& gravity) {
  m_world->setGravity(gravity);
  worldInfo().m_gravity = gravity;
  for (const auto& force : m_forces) {
    if (auto* weight = dynamic_cast<btDeformableGravityForce*>(force.get())) weight->m_gravity = gravity;
  }
}

void SoftWorldOfKind::addSoftBody(btSoftBody* body, double springStiffness) {
  if (m_softRigid != nullptr) {
    m_softRigid->addSoftBody(body);
  } else if (m_softMultiBody != nullptr) {
    m_softMultiBody->addSoftBody(body);
  } else {
    // The deformable solver's own rigid contacts: faces against rigid bodies (SDF_RDF) and
    // multibody links (SDF_MDF), as Bullet's deformable grasp demo sets them.
    body->m_cfg.collisions =
        btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDF | btSoftBody::fCollision::SDF_MDF;
    m_deformable->addSoftBody(body);
    m_forces.push_back(std::make_unique<btDeformableMassSpringForce>(btScalar(springStiffness),
                                                                     btScalar(kDeformableSpringDamping), true));
    m_deformable->addForce(body, m_forces.back().get());
    m_forces.push_back(std::make_unique<btDeformableGravityForce>(m_deformable->getGravity()));
    m_deformable->addForce(body, m_forces.back().get());
  }
}

void SoftWorldOfKind::removeSoftBody(btSoftBody* body) {
  if (m_softRigid != nullptr) {
    m_softRigid->removeSoftBody(body);
  } else if (m_softMultiBody != nullptr) {
    m_softMultiBody->removeSoftBody(body);
  } else {
    m_deformable->removeSoftBody(body);
  }
}

}  // namespace thintool::scenes
