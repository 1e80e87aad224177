// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example shows how a Bullet soft-body program switches to ThinTool: construct ThinTool's
// collision configuration instead of the stock one, register the tool with one call, and read
// the tool's contacts after each step. A thin plate presses a soft ball and holds it.

#include <thintool/thintool.h>

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <cstdio>

int main() {
  constexpr btScalar kTimeStep = btScalar(1) / 60;
  constexpr int kPressSteps = 120;  // 2 s at 0.5 m/s: 1 m down
  constexpr int kHoldSteps = 60;
  constexpr btScalar kPressSpeed = 0.5;

  // 1. ThinTool's configuration where btSoftBodyRigidBodyCollisionConfiguration was ...
  thintool::CollisionConfiguration collisionConfiguration;
  btCollisionDispatcher dispatcher(&collisionConfiguration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver constraintSolver;
  // ... and ThinTool's soft-body solver where btDefaultSoftBodySolver was: it has the last word.
  thintool::SoftBodySolver softBodySolver(collisionConfiguration);
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &constraintSolver, &collisionConfiguration,
                                 &softBodySolver);
  world.setGravity(btVector3(0, -10, 0));
  btSoftBodyWorldInfo& worldInfo = world.getWorldInfo();
  worldInfo.m_gravity = world.getGravity();

  btBoxShape groundShape(btVector3(20, 1, 20));
  btDefaultMotionState groundMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &groundMotion, &groundShape));
  world.addRigidBody(&ground);

  btSoftBody* ball = btSoftBodyHelpers::CreateEllipsoid(worldInfo, btVector3(0, 1.3, 0), btVector3(1, 1, 1), 63);
  ball->m_materials[0]->m_kLST = 0.5;
  ball->m_cfg.kDF = 0.5;
  ball->m_cfg.kPR = 50;
  ball->setTotalMass(1);
  ball->getCollisionShape()->setMargin(0.05);
  world.addSoftBody(ball);

  // A kinematic plate, 0.8 × 0.02 × 0.8 m, driven through its motion state as a haptic device would.
  btBoxShape plateShape(btVector3(0.4, 0.01, 0.4));
  btDefaultMotionState plateMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, 2.5, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &plateMotion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  world.addRigidBody(&plate);

  // 2. One call per tool.
  thintool::Tool& tool = thintool::addTool(world, plate);
  std::printf("%s: %u sample nodes\n", tool.name().c_str(), unsigned(tool.nodeCount()));

  // 3. Step, then read the tool's report.
  btScalar deepest = 0;
  for (int step = 0; step < kPressSteps + kHoldSteps; ++step) {
    btTransform pose;
    plateMotion.getWorldTransform(pose);
    if (step < kPressSteps) {
      pose.getOrigin().setY(pose.getOrigin().y() - kPressSpeed * kTimeStep);
    }
    plateMotion.setWorldTransform(pose);
    world.stepSimulation(kTimeStep, 1, kTimeStep);

    const thintool::ToolStepReport& report = tool.report();
    const thintool::ToolDiagnostics& d = report.diagnostics;
    deepest = std::max(deepest, btScalar(d.maxRemainingPenetration));
    if (step % 30 == 29) {
      std::printf("step %3d: %3u contacts, %3u excluded by check 1, %3u by check 2, force %6.2f N, %5.1f us\n",
                  step + 1, unsigned(d.detection.colliding), unsigned(d.detection.excludedByCheck1),
                  unsigned(d.detection.excludedByCheck2), report.wrench.force.y,
                  d.detectionMicroseconds + d.responseMicroseconds + d.lastWord.microseconds);
    }
  }
  std::printf("deepest soft face left inside the plate after a step: %.4f m\n", double(deepest));

  thintool::removeTool(world, plate);
  world.removeRigidBody(&plate);
  world.removeSoftBody(ball);
  delete ball;
  world.removeRigidBody(&ground);
  // The plate is 0.02 m thick: anything deeper than half of it means a face went through.
  return deepest < 0.01 ? 0 : 1;
}
