// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Pairs without a registered tool keep Bullet's stock behaviour bit for bit: they are processed by
// Bullet's own btSoftRigidCollisionAlgorithm object, and a world with ThinTool's configuration but
// no tool evolves exactly as a stock world does.
//
// Whole-world identity of the other bodies cannot be asked for once a tool changes anything:
// Bullet's hashed pair cache removes a pair by moving the last one into its slot, so a tool pair
// that appears or disappears a step earlier reorders every later pair, and with it the order in
// which another soft body's contacts are generated and solved (Gauss–Seidel). We saw it here:
// the stock run had the ball-1/plate pair at step 16, the ThinTool run did not, and the second
// ball's nodes differed in the last bits from step 56 on.

#include <thintool/thintool.h>

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidCollisionAlgorithm.h>
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
  int stockSoftPairs = 0;            // soft–rigid pairs run by Bullet's own algorithm
  int thinToolPairs = 0;             // soft–rigid pairs run by another algorithm
  int toolPairsOnStock = 0;          // pairs with the tool that Bullet's algorithm ran
};

void append(std::vector<btScalar>& out, const btVector3& v) { out.insert(out.end(), {v.x(), v.y(), v.z()}); }

void appendBall(std::vector<btScalar>& out, const btSoftBody& ball) {
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    append(out, ball.m_nodes[i].m_x);
    append(out, ball.m_nodes[i].m_v);
  }
}

// ThinToolWithFarTool: the plate is a tool, parked 50 m above the balls.
enum class Setup { Stock, ThinToolWithTool, ThinToolWithoutTool, ThinToolWithFarTool };
enum class SoftSolver { Bullets, ThinTools };

// Two balls 3 m apart; a kinematic plate presses the first, a dynamic box falls on the second.
Snapshot run(Setup setup, SoftSolver softSolverKind = SoftSolver::Bullets) {
  std::unique_ptr<btCollisionConfiguration> configuration;
  if (setup == Setup::Stock) {
    configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
  } else {
    configuration = std::make_unique<CollisionConfiguration>();
  }
  btCollisionDispatcher dispatcher(configuration.get());
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<btDefaultSoftBodySolver> softSolver;
  if (softSolverKind == SoftSolver::ThinTools) {
    softSolver = std::make_unique<SoftBodySolver>(static_cast<CollisionConfiguration&>(*configuration));
  } else {
    softSolver = std::make_unique<btDefaultSoftBodySolver>();
  }
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, configuration.get(), softSolver.get());
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
  const btScalar plateHeight = setup == Setup::ThinToolWithFarTool ? 50 : btScalar(2.6);
  btDefaultMotionState plateMotion(btTransform(btQuaternion::getIdentity(), btVector3(-3, plateHeight, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &plateMotion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  plate.setActivationState(DISABLE_DEACTIVATION);
  world.addRigidBody(&plate);
  const bool registered = setup == Setup::ThinToolWithTool || setup == Setup::ThinToolWithFarTool;
  if (registered) {
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
  btOverlappingPairCache* pairs = world.getBroadphase()->getOverlappingPairCache();
  for (int k = 0; k < pairs->getNumOverlappingPairs(); ++k) {
    const btBroadphasePair& pair = pairs->getOverlappingPairArray()[k];
    const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
    const bool soft = btSoftBody::upcast(a) != nullptr || btSoftBody::upcast(b) != nullptr;
    const bool withTool = a == &plate || b == &plate;
    if (!soft || pair.m_algorithm == nullptr || (btSoftBody::upcast(a) && btSoftBody::upcast(b))) continue;
    if (dynamic_cast<btSoftRigidCollisionAlgorithm*>(pair.m_algorithm) != nullptr) {
      ++snapshot.stockSoftPairs;
      snapshot.toolPairsOnStock += withTool ? 1 : 0;
    } else {
      ++snapshot.thinToolPairs;
    }
  }
  appendBall(snapshot.firstBall, *balls[0]);
  appendBall(snapshot.secondBall, *balls[1]);
  append(snapshot.box, box.getWorldTransform().getOrigin());
  for (int i = 0; i < 3; ++i) append(snapshot.box, box.getWorldTransform().getBasis()[i]);
  append(snapshot.box, box.getLinearVelocity());

  if (registered) removeTool(world, plate);
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

TEST(StockPairs, UnregisteredPairsRunOnBulletsOwnAlgorithm) {
  const Snapshot withTool = run(Setup::ThinToolWithTool);
  // Ground–ball 1, ground–ball 2 and box–ball 2 are Bullet's; plate–ball 1 is ThinTool's, twice:
  // the plate's own pair stands idle while its swept proxy's pair does the work.
  EXPECT_EQ(withTool.stockSoftPairs, 3);
  EXPECT_EQ(withTool.thinToolPairs, 2);
  EXPECT_EQ(withTool.toolPairsOnStock, 0);
  // The tool's own ball is ThinTool's: it must differ from a stock run, or the test proved nothing.
  EXPECT_FALSE(bitIdentical(run(Setup::Stock).firstBall, withTool.firstBall));
}

TEST(StockPairs, WithoutToolsThinToolsConfigurationIsStockBullet) {
  const Snapshot stock = run(Setup::Stock);
  const Snapshot none = run(Setup::ThinToolWithoutTool);
  EXPECT_EQ(none.thinToolPairs, 0);
  EXPECT_TRUE(bitIdentical(stock.firstBall, none.firstBall));
  EXPECT_TRUE(bitIdentical(stock.secondBall, none.secondBall));
  EXPECT_TRUE(bitIdentical(stock.box, none.box));
}

// ThinTool's soft-body solver runs its own copy of Bullet's solve, stage by stage, for every body
// the last word looks at (to survey the body in the solve's last pass over its nodes): with the tool
// far from both balls, nothing else of ThinTool's touches them, and they must move bit for bit as
// under Bullet's own solver, pressure, links, the ground's and the falling box's contacts included.
TEST(StockPairs, ThinToolsCopyOfBulletsSolveMovesBodiesAsBulletsOwn) {
  const Snapshot bullets = run(Setup::ThinToolWithFarTool, SoftSolver::Bullets);
  const Snapshot thinTools = run(Setup::ThinToolWithFarTool, SoftSolver::ThinTools);
  EXPECT_TRUE(bitIdentical(bullets.firstBall, thinTools.firstBall));
  EXPECT_TRUE(bitIdentical(bullets.secondBall, thinTools.secondBall));
  EXPECT_TRUE(bitIdentical(bullets.box, thinTools.box));
  // The box fell onto the second ball (from 3 m): the soft contacts of the solve had work to do.
  EXPECT_LT(thinTools.box[1], btScalar(2.9));
}

}  // namespace
}  // namespace thintool
