// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers

// A link of a Featherstone multibody as a tool, in Bullet's soft–multibody world (PyBullet's
// default soft world): a thin finger on a prismatic joint, driven down by a motor into a soft ball,
// or let fall onto it. The link collider is registered like any collision object; the multibody
// moves it, and the tissue's reaction moves the multibody back through its joints.

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

// A soft ball of radius 0.5 m and 1 kg held by its pressure, resting on the ground at the origin,
// added to world; the caller removes and deletes it.
btSoftBody* addBall(btSoftMultiBodyDynamicsWorld& world) {
  btSoftBody* ball = btSoftBodyHelpers::CreateEllipsoid(world.getWorldInfo(), btVector3(0, 0.5, 0),
                                                        btVector3(0.5, 0.5, 0.5), 256);
  ball->m_materials[0]->m_kLST = 0.5;
  ball->m_cfg.piterations = 4;
  ball->m_cfg.kPR = 50;
  ball->getCollisionShape()->setMargin(0.02);
  ball->setTotalMass(1);
  world.addSoftBody(ball);
  return ball;
}

// A fixed base at basePosition and one prismatic link along -y of the given mass carrying a box,
// driven by a velocity motor, or free on its joint when motorImpulse is 0 (N s a step); added to the
// world, removed with it.
struct PrismaticLink {
  btMultiBody body;
  btBoxShape shape;
  btMultiBodyLinkCollider collider;
  btMultiBodyJointMotor motor;
  btSoftMultiBodyDynamicsWorld& world;
  bool motorised;

  PrismaticLink(btSoftMultiBodyDynamicsWorld& w, const btVector3& basePosition, const btVector3& halfExtents,
                btScalar mass, btScalar speed, btScalar motorImpulse = 1000)
      : body(1, 0, btVector3(0, 0, 0), true, false), shape(halfExtents), collider(&body, 0),
        motor(&body, 0, speed, motorImpulse), world(w), motorised(motorImpulse > 0) {
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
    if (motorised) world.addMultiBodyConstraint(&motor);
  }
  ~PrismaticLink() {
    if (motorised) world.removeMultiBodyConstraint(&motor);
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

  btSoftBody* ball = addBall(world);

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

// What a dynamic tool dropped onto a soft ball did: where it ended, the deepest node inside it at
// the end of any step, and the momentum balance over the last two seconds.
struct Drop {
  double height = 0;     // the tool's origin at the end (m); the ball's top is at 1 m
  double deepest = 0;    // m
  double reacted = 0;    // Σ report().reaction.force.y · dt (N s)
  double expected = 0;   // m g T + m (v_y(start) − v_y(end)): what the tissue must have given (N s)
  double weightTime = 0; // m g T (N s)
};

// A soft ball on the ground; toolBody (of mass kg, its shape a box shape) falls 0.5 m onto it and
// is watched for five seconds. verticalSpeed reads the tool's upward speed (m/s).
template <typename VerticalSpeed>
Drop dropOntoABall(SoftMultiBodyWorld& w, btCollisionObject& toolBody, const btBoxShape& shape, double mass,
                   const VerticalSpeed& verticalSpeed) {
  btSoftMultiBodyDynamicsWorld& world = w.world;
  btBoxShape groundShape(btVector3(5, 0.5, 5));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -0.5, 0)));
  world.addRigidBody(&ground);
  btSoftBody* ball = addBall(world);
  ball->m_cfg.kDF = 1;

  Tool& tool = addTool(world, toolBody);
  Drop drop;
  constexpr int kSteps = 300;
  constexpr int kWatchedFrom = 180;
  double speedAtWatch = 0;
  for (int step = 0; step < kSteps; ++step) {
    if (step == kWatchedFrom) speedAtWatch = verticalSpeed();
    world.stepSimulation(kStep, 1, kStep);
    for (int i = 0; i < ball->m_nodes.size(); ++i) {
      EXPECT_TRUE(std::isfinite(ball->m_nodes[i].m_x.length2())) << "step " << step;
      drop.deepest = std::max(drop.deepest, depthIn(shape, toolBody.getWorldTransform(), ball->m_nodes[i].m_x));
    }
    EXPECT_TRUE(std::isfinite(verticalSpeed())) << "step " << step;
    if (step >= kWatchedFrom) drop.reacted += double(tool.report().reaction.force.y) * double(kStep);
  }
  drop.height = toolBody.getWorldTransform().getOrigin().y();
  drop.weightTime = mass * 10 * (kSteps - kWatchedFrom) * double(kStep);
  drop.expected = drop.weightTime + mass * (verticalSpeed() - speedAtWatch);

  removeTool(world, toolBody);
  world.removeSoftBody(ball);
  delete ball;
  world.removeRigidBody(&ground);
  return drop;
}

void expectRestsOnTheBall(const Drop& drop) {
  EXPECT_GT(drop.height, 0.6) << "the tool rests on the ball, not on the ground";
  // Resting on the ball's top (1 m) untouched would leave the plate's centre its half thickness and
  // the skin higher (1.03 m); friction, on by default, keeps the top from spreading under the plate.
  EXPECT_LT(drop.height, 1.0 + 0.01 + 0.02) << "the tool pressed into the ball";
  EXPECT_EQ(drop.deepest, 0) << "no soft node inside the tool at the end of a step";
  EXPECT_NEAR(drop.reacted, drop.expected, 0.1 * drop.weightTime) << "the reported reaction is what moved the tool";
}

// A dynamic link takes the tissue's reaction through the multibody's joints: a plate free on a
// prismatic joint, dropped onto a soft ball, rests on it (taken as kinematic, with no reaction, it
// would push the ball's top down to the ground), and the reaction the report gives balances its
// momentum.
TEST(MultiBodyTool, AFreeLinkDroppedOntoABallRestsOnIt) {
  SoftMultiBodyWorld w;
  const btScalar mass = btScalar(0.5);
  PrismaticLink plate(w.world, btVector3(0, 1.5, 0), btVector3(0.8, 0.01, 0.8), mass, 0, 0);
  // The joint's axis points down.
  const Drop drop = dropOntoABall(w, plate.collider, plate.shape, mass, [&] { return -plate.body.getJointVel(0); });
  expectRestsOnTheBall(drop);
}

// The same drop with a dynamic btRigidBody held to vertical motion: the same rest, the same balance.
TEST(MultiBodyTool, AFreeRigidPlateDroppedOntoABallRestsOnIt) {
  SoftMultiBodyWorld w;
  const btScalar mass = btScalar(0.5);
  btBoxShape shape(btVector3(0.8, 0.01, 0.8));
  btVector3 inertia;
  shape.calculateLocalInertia(mass, inertia);
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(mass, nullptr, &shape, inertia));
  plate.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.5, 0)));
  plate.setLinearFactor(btVector3(0, 1, 0));
  plate.setAngularFactor(btVector3(0, 0, 0));
  w.world.addRigidBody(&plate);
  const Drop drop = dropOntoABall(w, plate, shape, mass, [&] { return double(plate.getLinearVelocity().y()); });
  w.world.removeRigidBody(&plate);
  expectRestsOnTheBall(drop);
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
