// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/Clamp.h>
#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>
#include <thintool/core/Error.h>

#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace thintool {

struct Clamp::Parts {
  btBoxShape jawShape;
  btCylinderShapeX handleShape;
  std::array<btDefaultMotionState, 2> jawMotion;
  btDefaultMotionState handleMotion;
  std::array<std::unique_ptr<btRigidBody>, 2> jaws;
  std::unique_ptr<btRigidBody> handle;

  Parts(const btVector3& jawHalf, btScalar handleRadius)
      : jawShape(jawHalf), handleShape(btVector3(jawHalf.x(), handleRadius, handleRadius)) {}
};

namespace {

// The handle reaches back from the hinge, its centre half a jaw's length behind it.
btTransform handleBodyPose(const btTransform& handlePose, const Vec3& jawHalfExtents) {
  return handlePose * btTransform(btQuaternion::getIdentity(), btVector3(-btScalar(jawHalfExtents.x), 0, 0));
}

std::unique_ptr<btRigidBody> kinematicBody(btMotionState& motion, btCollisionShape& shape) {
  auto body = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &shape));
  body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  body->setActivationState(DISABLE_DEACTIVATION);
  return body;
}

}  // namespace

Clamp::Clamp(btSoftRigidDynamicsWorld& world, const ClampSettings& settings, const btTransform& handlePose,
             Real opening)
    : m_world(world), m_settings(settings), m_handlePose(handlePose) {
  const Vec3& half = settings.jawHalfExtents;
  std::ostringstream problem;
  if (!(isFinite(half) && half.x > 0 && half.y > 0 && half.z > 0)) {
    problem << "jawHalfExtents must be finite and > 0 m";
  } else if (!(settings.maxOpening > 0 && settings.maxOpening < kPi)) {
    problem << "maxOpening must lie in (0, pi) rad, got " << settings.maxOpening;
  }
  if (!problem.str().empty()) {
    throw Error("clamp '" + settings.name + "': " + problem.str());
  }
  m_parts = std::make_unique<Parts>(toBt(half), btScalar(half.y));
  m_parts->jawShape.setMargin(btScalar(std::min<Real>(0.001, half.y / 2)));
  m_opening = std::clamp<Real>(opening, 0, settings.maxOpening);

  static const char* const kJawNames[2] = {" upper jaw", " lower jaw"};
  for (int i = 0; i < 2; ++i) {
    m_parts->jawMotion[i].setWorldTransform(jawPose(i, handlePose, m_opening));
    m_parts->jaws[i] = kinematicBody(m_parts->jawMotion[i], m_parts->jawShape);
    m_jawBodies[i] = m_parts->jaws[i].get();
    world.addRigidBody(m_jawBodies[i]);
    ToolOptions options = settings.jawOptions;
    options.name = settings.name + kJawNames[i];
    try {
      m_jawTools[i] = &addTool(world, *m_jawBodies[i], options);
    } catch (...) {
      for (int k = 0; k <= i; ++k) {
        if (k < i) removeTool(world, *m_jawBodies[k]);
        world.removeRigidBody(m_jawBodies[k]);
      }
      throw;
    }
  }
  // The handle collides with nothing (mask 0).
  m_parts->handleMotion.setWorldTransform(handleBodyPose(handlePose, half));
  m_parts->handle = kinematicBody(m_parts->handleMotion, m_parts->handleShape);
  m_handle = m_parts->handle.get();
  world.addRigidBody(m_handle, 0, 0);
}

Clamp::~Clamp() {
  m_world.removeRigidBody(m_handle);
  for (int i = 0; i < 2; ++i) {
    removeTool(m_world, *m_jawBodies[i]);
    m_world.removeRigidBody(m_jawBodies[i]);
  }
}

btTransform Clamp::jawPose(int i, const btTransform& handlePose, Real opening) const {
  const Vec3& half = m_settings.jawHalfExtents;
  const btScalar side = i == 0 ? 1 : -1;
  // Each jaw turns by half the opening about the hinge (the handle's z axis); its inner face
  // passes through the hinge.
  const btQuaternion turn(btVector3(0, 0, 1), side * btScalar(opening / 2));
  const btTransform hinge(turn, btVector3(0, 0, 0));
  const btTransform alongJaw(btQuaternion::getIdentity(), btVector3(btScalar(half.x), side * btScalar(half.y), 0));
  return handlePose * hinge * alongJaw;
}

void Clamp::setPose(const btTransform& handlePose, Real opening) {
  m_handlePose = handlePose;
  m_opening = std::isfinite(opening) ? std::clamp<Real>(opening, 0, m_settings.maxOpening) : m_opening;
  for (int i = 0; i < 2; ++i) {
    m_parts->jawMotion[i].setWorldTransform(jawPose(i, handlePose, m_opening));
  }
  m_parts->handleMotion.setWorldTransform(handleBodyPose(handlePose, m_settings.jawHalfExtents));
}

ClampForces Clamp::forces() {
  ClampForces out;
  for (int i = 0; i < 2; ++i) {
    const ToolStepReport& report = jaw(i).report();
    out.onJaw[i] = report.wrench.force + report.holdWrench.force;
    out.onBody -= out.onJaw[i];
    // The tissue pushes a jaw away from the other one: along +y of the upper jaw, -y of the lower.
    const btVector3 outward = m_jawBodies[i]->getWorldTransform().getBasis().getColumn(1) * (i == 0 ? 1 : -1);
    out.grip += dot(out.onJaw[i], toVec3(outward)) / 2;
  }
  return out;
}

}  // namespace thintool
