// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers

// A link of a Featherstone multibody as a tool, in Bullet's soft–multibody world (PyBullet's
// default soft world): a thin finger on a prismatic joint, driven down by a motor into a soft ball.
// The link collider is registered like any collision object; the multibody moves it, and ThinTool
// follows it as it follows a kinematic body (the finger takes no reaction from the tissue).

#include <thintool/thintool.h>

#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftMultiBodyDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace thintool {
namespace {

constexpr btScalar kStep = btScalar(1) / 60;

double depthIn(const btConvexShape& shape, const btTransform& pose, const btVector3& point) {
  btGjkEpaSolver2::sResults results;
  const btScalar distance = btGjkEpaSolver2::SignedDistance(point, 0, &shape, pose, results);
  return distance < 0 ? -double(distance) : 0;
}

// A soft multibody world on ThinTool's configuration and solver, gravity 10 m/s² down.
struct SoftMultiBodyWorld {
  CollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  SoftBodySolver softSolver{configuration};
  btSoftMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration, &softSolver};

  SoftMultiBodyWorld() {
    world.setGravity(btVector3(0, -10, 0));
    world.getWorldInfo().m_gravity = btVector3(0, -10, 0);
    world.getWorldInfo().m_sparsesdf.Initialize();
  }
};

// A fixed base at basePosition and one prismatic link along -y of the given mass carrying a box,
// driven by a velocity motor; added to the world, removed with it.
struct PrismaticLink {
  btMultiBody body;
  btBoxShape shape;
  btMultiBodyLinkCollider collider;
  btMultiBodyJointMotor motor;
  btSoftMultiBodyDynamicsWorld& world;

  PrismaticLink(btSoftMultiBodyDynamicsWorld& w, const btVector3& basePosition, const btVector3& halfExtents,
                btScalar mass, btScalar speed)
      : body(1, 0, btVector3(0, 0, 0), true, false), shape(halfExtents), collider(&body, 0),
        motor(&body, 0, speed, btScalar(1000)), world(w) {
    body.setBasePos(basePosition);
    btVector3 inertia;
    shape.calculateLocalInertia(mass, inertia);
    body.setupPrismatic(0, mass, inertia, -1, btQuaternion::getIdentity(), btVector3(0, -1, 0), btVector3(0, 0, 0),
                        btVector3(0, 0, 0), true);
    body.finalizeMultiDof();
    world.addMultiBody(&body);
    collider.setCollisionShape(&shape);
    body.getLink(0).m_collider = &collider;
    btAlignedObjectArray<btQuaternion> worldToLocal;
    btAlignedObjectArray<btVector3> localOrigin;
    body.updateCollisionObjectWorldTransforms(worldToLocal, localOrigin);
    world.addCollisionObject(&collider, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    world.addMultiBodyConstraint(&motor);
  }
  ~PrismaticLink() {
    world.removeMultiBodyConstraint(&motor);
    world.removeCollisionObject(&collider);
    world.removeMultiBody(&body);
  }
  PrismaticLink(const PrismaticLink&) = delete;
  PrismaticLink& operator=(const PrismaticLink&) = delete;
};

TEST(MultiBodyTool, AFingerLinkPressedIntoABallKeepsItsNodesOut) {
  SoftMultiBodyWorld w;
  btSoftMultiBodyDynamicsWorld& world = w.world;

  btBoxShape groundShape(btVector3(5, 0.5, 5));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -0.5, 0)));
  world.addRigidBody(&ground);

  btSoftBody* ball = btSoftBodyHelpers::CreateEllipsoid(world.getWorldInfo(), btVector3(0, 0.5, 0),
                                                        btVector3(0.5, 0.5, 0.5), 256);
  ball->m_materials[0]->m_kLST = 0.5;
  ball->m_cfg.piterations = 4;
  ball->m_cfg.kPR = 50;
  ball->getCollisionShape()->setMargin(0.02);
  ball->setTotalMass(1);
  world.addSoftBody(ball);

  // A fixed base 1.5 m up and one prismatic link along -y carrying a plate 2 cm thick, driven down
  // at 0.5 m/s whatever the ball pushes back: the motor holds the speed.
  PrismaticLink finger(world, btVector3(0, 1.5, 0), btVector3(0.2, 0.01, 0.2), btScalar(0.5), btScalar(0.5));
  btMultiBodyLinkCollider& collider = finger.collider;
  const btBoxShape& plateShape = finger.shape;
  Tool& tool = addTool(world, collider);
  EXPECT_EQ(tool.rigidBody(), nullptr);
  int stepsWithContacts = 0;
  double deepest = 0;
  double lowest = 10;
  for (int step = 0; step < 120; ++step) {
    world.stepSimulation(kStep, 1, kStep);
    stepsWithContacts += tool.report().contacts.empty() ? 0 : 1;
    lowest = std::min(lowest, double(collider.getWorldTransform().getOrigin().y()));
    for (int i = 0; i < ball->m_nodes.size(); ++i) {
      ASSERT_TRUE(std::isfinite(ball->m_nodes[i].m_x.length2())) << "step " << step;
      deepest = std::max(deepest, depthIn(plateShape, collider.getWorldTransform(), ball->m_nodes[i].m_x));
    }
  }
  EXPECT_LT(lowest, 0.8) << "the finger went into the ball (its top at 1 m)";
  EXPECT_GT(stepsWithContacts, 0);
  EXPECT_EQ(deepest, 0) << "no soft node inside the finger at the end of a step";
  EXPECT_TRUE(tool.report().diagnostics.lastWord.ran);

  removeTool(world, collider);
  world.removeSoftBody(ball);
  delete ball;
  world.removeRigidBody(&ground);
}

// The load read-back in the soft multibody world: a cloth laid on a multibody's link, held still by
// its motor; once the cloth rests, the link's report carries its weight.
TEST(MultiBodyTool, ALinkCarriesTheWeightOfAClothRestingOnIt) {
  SoftMultiBodyWorld w;
  btSoftMultiBodyDynamicsWorld& world = w.world;

  PrismaticLink platform(world, btVector3(0, 0.5, 0), btVector3(0.5, 0.01, 0.5), 5, 0);  // the motor holds it
  btMultiBodyLinkCollider& collider = platform.collider;
  Tool& tool = addTool(world, collider);

  const btScalar h = btScalar(0.58);
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-0.4f, h, -0.4f),
                                                     btVector3(0.4f, h, -0.4f), btVector3(-0.4f, h, 0.4f),
                                                     btVector3(0.4f, h, 0.4f), 9, 9, 0, true);
  cloth->getCollisionShape()->setMargin(btScalar(0.02));
  cloth->setTotalMass(2);
  world.addSoftBody(cloth);
  const double weight = 2 * 10;
  double carried = 0;
  int steps = 0;
  for (int i = 0; i < 240; ++i) {
    world.stepSimulation(btScalar(1.0 / 120), 1, btScalar(1.0 / 120));
    const ToolStepReport& report = tool.report();
    ASSERT_TRUE(isFinite(report.holdWrench.force) && isFinite(report.wrench.force)) << "step " << i;
    if (i >= 180) {
      carried += report.wrench.force.y + report.holdWrench.force.y;
      ++steps;
    }
  }
  EXPECT_NEAR(carried / steps, -weight, 0.05 * weight) << "the cloth presses down on the link";
  EXPECT_NEAR(collider.getWorldTransform().getOrigin().y(), 0.5, 0.01) << "the motor held the link";

  world.removeSoftBody(cloth);
  delete cloth;
  removeTool(world, collider);
}

}  // namespace
}  // namespace thintool
