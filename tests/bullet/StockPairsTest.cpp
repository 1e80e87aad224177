// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Pairs without a registered tool keep Bullet's stock behaviour bit for bit: a scene run with
// ThinTool's configuration and a registered tool, and the same scene on the stock configuration,
// leave the untouched soft body and the other rigid bodies in exactly the same state.

#include <thintool/thintool.h>

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

namespace thintool {
namespace {

struct Snapshot {
  std::vector<btScalar> firstBall;   // node positions and velocities
  std::vector<btScalar> secondBall;
  std::vector<btScalar> box;         // transform and velocity of the box dropped on the second ball
};

void append(std::vector<btScalar>& out, const btVector3& v) { out.insert(out.end(), {v.x(), v.y(), v.z()}); }

void appendBall(std::vector<btScalar>& out, const btSoftBody& ball) {
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    append(out, ball.m_nodes[i].m_x);
    append(out, ball.m_nodes[i].m_v);
  }
}

enum class Setup { Stock, ThinToolWithTool, ThinToolWithoutTool };

// Two balls 3 m apart; a kinematic plate presses the first, a dynamic box falls on the second.
Snapshot run(Setup setup) {
  std::unique_ptr<btCollisionConfiguration> configuration;
  if (setup == Setup::Stock) {
    configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
  } else {
    configuration = std::make_unique<CollisionConfiguration>();
  }
  btCollisionDispatcher dispatcher(configuration.get());
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDefaultSoftBodySolver softSolver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, configuration.get(), &softSolver);
  world.setGravity(btVector3(0, -10, 0));
  world.getWorldInfo().m_gravity = world.getGravity();

  btBoxShape groundShape(btVector3(20, 1, 20));
  btDefaultMotionState groundMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &groundMotion, &groundShape));
  world.addRigidBody(&ground);

  btSoftBody* balls[2];
  for (int k = 0; k < 2; ++k) {
    balls[k] = btSoftBodyHelpers::CreateEllipsoid(world.getWorldInfo(), btVector3(k == 0 ? -3 : 3, 1.3, 0),
                                                  btVector3(1, 1, 1), 63);
    balls[k]->m_cfg.kPR = 50;
    balls[k]->setTotalMass(1);
    world.addSoftBody(balls[k]);
  }

  btBoxShape plateShape(btVector3(0.4, 0.01, 0.4));
  btDefaultMotionState plateMotion(btTransform(btQuaternion::getIdentity(), btVector3(-3, 2.6, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &plateMotion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  plate.setActivationState(DISABLE_DEACTIVATION);
  world.addRigidBody(&plate);
  if (setup == Setup::ThinToolWithTool) {
    addTool(world, plate);
  }

  btBoxShape boxShape(btVector3(0.2, 0.2, 0.2));
  btVector3 inertia;
  boxShape.calculateLocalInertia(1, inertia);
  btDefaultMotionState boxMotion(btTransform(btQuaternion::getIdentity(), btVector3(3.1, 3, 0)));
  btRigidBody box(btRigidBody::btRigidBodyConstructionInfo(1, &boxMotion, &boxShape, inertia));
  world.addRigidBody(&box);

  const btScalar dt = btScalar(1) / 60;
  for (int step = 0; step < 150; ++step) {
    btTransform pose;
    plateMotion.getWorldTransform(pose);
    pose.getOrigin().setY(pose.getOrigin().y() - btScalar(0.5) * dt);
    plateMotion.setWorldTransform(pose);
    world.stepSimulation(dt, 1, dt);
  }

  Snapshot snapshot;
  appendBall(snapshot.firstBall, *balls[0]);
  appendBall(snapshot.secondBall, *balls[1]);
  append(snapshot.box, box.getWorldTransform().getOrigin());
  for (int i = 0; i < 3; ++i) append(snapshot.box, box.getWorldTransform().getBasis()[i]);
  append(snapshot.box, box.getLinearVelocity());

  if (setup == Setup::ThinToolWithTool) removeTool(world, plate);
  world.removeRigidBody(&box);
  world.removeRigidBody(&plate);
  for (btSoftBody* ball : balls) {
    world.removeSoftBody(ball);
    delete ball;
  }
  world.removeRigidBody(&ground);
  return snapshot;
}

bool bitIdentical(const std::vector<btScalar>& a, const std::vector<btScalar>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0;
}

TEST(StockPairs, UnregisteredPairsMatchAStockRunBitForBit) {
  const Snapshot stock = run(Setup::Stock);
  const Snapshot withTool = run(Setup::ThinToolWithTool);
  EXPECT_TRUE(bitIdentical(stock.secondBall, withTool.secondBall));
  EXPECT_TRUE(bitIdentical(stock.box, withTool.box));
  // The tool's own ball is ThinTool's: it must differ, or the test proved nothing.
  EXPECT_FALSE(bitIdentical(stock.firstBall, withTool.firstBall));
}

TEST(StockPairs, WithoutToolsThinToolsConfigurationIsStockBullet) {
  const Snapshot stock = run(Setup::Stock);
  const Snapshot none = run(Setup::ThinToolWithoutTool);
  EXPECT_TRUE(bitIdentical(stock.firstBall, none.firstBall));
  EXPECT_TRUE(bitIdentical(stock.secondBall, none.secondBall));
  EXPECT_TRUE(bitIdentical(stock.box, none.box));
}

}  // namespace
}  // namespace thintool
