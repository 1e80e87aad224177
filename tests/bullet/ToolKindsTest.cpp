// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Kinematic tools with substeps, dynamic tools that feel the tissue, compound tools, and tools
// registered after their pairs already exist.

#include "SoftBallScene.h"
#include "SoftWorld.h"

#include <BulletSoftBody/btSoftBodyHelpers.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <memory>

namespace thintool::scenes {
namespace {

TEST(ToolKinds, KinematicToolWithSubsteps) {
  // The pose jumps in the first of four substeps; the other three see the tool at rest.
  PressSettings settings;
  settings.scene.timeStep = 1.0 / 60;
  settings.scene.substeps = 4;
  settings.speed = 1;
  const PressResult r = runPress(settings);
  EXPECT_EQ(r.metrics.crossed, 0);
  EXPECT_FALSE(r.metrics.everInside);
  EXPECT_GT(r.maxContacts, 0);
}

TEST(ToolKinds, CompoundToolUsesEveryChild) {
  PressSettings settings;
  settings.scene.tool = ToolShape::SplitPlate;
  settings.scene.timeStep = 1.0 / 60;
  settings.speed = 1;
  const PressResult r = runPress(settings);
  EXPECT_EQ(r.metrics.crossed, 0);
  EXPECT_FALSE(r.metrics.everInside);

  SceneSettings sceneSettings;
  sceneSettings.tool = ToolShape::SplitPlate;
  SoftBallScene scene(sceneSettings);
  ASSERT_EQ(scene.tool()->pieceCount(), 2u);
  scene.settle();
  // From just above the skin, 5 mm a step: both children are processed against the ball and
  // their contacts name them.
  const double top = scene.ballTop();
  Index mostPairs = 0;
  bool contacts = false;
  for (int i = 0; i < 8; ++i) {
    scene.step(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(top + 0.06 - 0.005 * i), 0)));
    const ToolStepReport& report = scene.tool()->report();
    mostPairs = std::max(mostPairs, report.diagnostics.pairs);
    for (const auto& contact : report.contacts) {
      contacts = true;
      EXPECT_LT(contact.piece, 2u);
      EXPECT_EQ(contact.softBody, &scene.ball());
    }
  }
  EXPECT_EQ(mostPairs, 2u);
  EXPECT_TRUE(contacts);
}

TEST(ToolKinds, DynamicToolRestsOnTheBallAndFeelsIt) {
  SceneSettings settings;
  SoftBallScene scene(settings);
  scene.settle();
  const double top = scene.ballTop();
  scene.makeToolDynamic(0.5, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(top + 0.3), 0)));
  double meanForce = 0;
  double lowest = 1e9;
  int counted = 0;
  int nodesOnTop = 0;
  const btRigidBody& plate = scene.toolBody();
  const btSoftBody& ball = scene.ball();
  for (int i = 0; i < 300; ++i) {
    scene.step();
    const btVector3 centre = plate.getWorldTransform().getOrigin();
    for (int n = 0; n < ball.m_nodes.size(); ++n) {
      const btVector3& x = ball.m_nodes[n].m_x;
      nodesOnTop += std::abs(x.x() - centre.x()) < 0.4 && std::abs(x.z() - centre.z()) < 0.4 && x.y() > centre.y();
    }
    if (i >= 180) {
      meanForce += scene.tool()->report().wrench.force.y;
      lowest = std::min(lowest, double(centre.y()));
      ++counted;
    }
  }
  meanForce /= counted;
  EXPECT_EQ(nodesOnTop, 0) << "no node came through the plate";
  EXPECT_GT(lowest, scene.ballMeanHeight()) << "it never sank into the ball";
  // Its weight is 5 N, carried by the projection's reaction alone.
  EXPECT_GT(meanForce, 2.5);
  EXPECT_LT(meanForce, 10);
}

TEST(ToolKinds, ADynamicToolSetDownByHandIsSweptFromThere) {
  // Set down by hand just above the ball, declared a jump and launched at 30 m/s, the plate passes
  // the ball's top within its first step: Bullet integrates a dynamic body after the collision
  // pass, so the last word must sweep that motion from where the plate was set down. Without the
  // solver's holds nothing else keeps the nodes it passed below it.
  SceneSettings settings;
  settings.toolOptions.bullet.holdInSolver = false;
  SoftBallScene scene(settings);
  scene.settle();
  const double halfThickness = scene.toolBox().halfExtents.y;
  scene.makeToolDynamic(5, btTransform(btQuaternion::getIdentity(),
                                       scene.aboveBall(scene.ballTop() + scene.softMargin() + halfThickness + 0.01)));
  btRigidBody& plate = scene.toolBody();
  plate.setLinearVelocity(btVector3(0, -30, 0));
  scene.tool()->resetMotion();
  scene.step();
  const ToolBox box = scene.toolBox();
  ASSERT_LT(box.origin.y, scene.ballTop()) << "the plate went past the ball's top";
  const btSoftBody& ball = scene.ball();
  int above = 0;
  for (int n = 0; n < ball.m_nodes.size(); ++n) {
    const btVector3& x = ball.m_nodes[n].m_x;
    above += std::abs(x.x() - box.origin.x) < box.halfExtents.x && std::abs(x.z() - box.origin.z) < box.halfExtents.z &&
             x.y() > box.origin.y - box.halfExtents.y;
  }
  EXPECT_EQ(above, 0) << "nodes the plate passed were left above its underside";
}

// A hanging sheet, 1 m square in the plane x = 0, its middle node pinned and the rest free, and a
// 0.1 kg plate 2 × 30 × 30 cm, face on to the sheet with its centre at x = plateX, registered as a
// tool; no gravity.
struct PinnedSheetAndPlate {
  static constexpr int kMiddle = 12;  // the 5 × 5 patch's centre, at (0, 1, 0)
  SoftWorld soft{btVector3(0, 0, 0)};
  btSoftBody* sheet = nullptr;
  btBoxShape plateShape{btVector3(0.01, 0.15, 0.15)};
  btDefaultMotionState motion;
  std::unique_ptr<btRigidBody> plate;

  explicit PinnedSheetAndPlate(btScalar plateX)
      : motion(btTransform(btQuaternion::getIdentity(), btVector3(plateX, 1, 0))) {
    sheet = btSoftBodyHelpers::CreatePatch(soft.world.getWorldInfo(), btVector3(0, 0.5, -0.5),
                                           btVector3(0, 0.5, 0.5), btVector3(0, 1.5, -0.5), btVector3(0, 1.5, 0.5),
                                           5, 5, 0, true);
    sheet->getCollisionShape()->setMargin(0.01);
    sheet->setTotalMass(0.1);
    sheet->setMass(kMiddle, 0);
    soft.world.addSoftBody(sheet);
    btVector3 inertia;
    plateShape.calculateLocalInertia(0.1, inertia);
    plate = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0.1, &motion, &plateShape, inertia));
    plate->setActivationState(DISABLE_DEACTIVATION);
    soft.world.addRigidBody(plate.get());
    plate->setGravity(btVector3(0, 0, 0));
    addTool(soft.world, *plate);
  }
  ~PinnedSheetAndPlate() {
    removeTool(soft.world, *plate);
    soft.world.removeRigidBody(plate.get());
    soft.world.removeSoftBody(sheet);
    delete sheet;
  }
  const btVector3& pinned() const { return sheet->m_nodes[kMiddle].m_x; }
};

TEST(ToolKinds, APinnedNodeStopsAFastDynamicToolBeforeItReachesIt) {
  // The plate thrown face first at the sheet's middle at 20 m/s, 0.33 m a step at 60 Hz. Its first
  // step ends 0.16 m short of the sheet, beyond the reach of that step's last word; its second
  // would carry it through the pinned node, which nothing can move. The node must stop it there,
  // as a wall would: at the end of the first step, from where the plate will be able to reach it
  // in the next.
  PinnedSheetAndPlate scene(-0.5);
  ASSERT_LT(scene.pinned().distance(btVector3(0, 1, 0)), 1e-5);
  scene.plate->setLinearVelocity(btVector3(20, 0, 0));
  const btScalar dt = btScalar(1) / 60;
  btScalar farthest = -1;
  for (int step = 0; step < 6; ++step) {
    scene.soft.world.stepSimulation(dt, 1, dt);
    farthest = btMax(farthest, scene.plate->getWorldTransform().getOrigin().x() +
                                   scene.plateShape.getHalfExtentsWithMargin().x());
  }
  EXPECT_LT(farthest, btScalar(0.005)) << "the plate's front went past the pinned node at x = 0";
}

TEST(ToolKinds, APinnedNodeHoldsOffADynamicToolPushedAgainstIt) {
  // The plate set 0.02 m from the sheet and pushed at it by a steady 2 N. The node's stop at the
  // end of a step comes after the plate has moved; the next step's reactions to the free nodes
  // come before it moves again, and alone they would let the push carry the plate over the node a
  // step at a time. The plate may tip and slide off the node, as a plate pushed onto a point would,
  // but the node must never end a step inside it.
  PinnedSheetAndPlate scene(-0.03);
  const btScalar dt = btScalar(1) / 60;
  const btVector3 half = scene.plateShape.getHalfExtentsWithMargin();
  btScalar closest = 1;  // the node's least distance outside the plate's faces (m); < 0: inside
  for (int step = 0; step < 60; ++step) {
    scene.plate->applyCentralForce(btVector3(2, 0, 0));
    scene.soft.world.stepSimulation(dt, 1, dt);
    const btVector3 local = scene.plate->getWorldTransform().invXform(scene.pinned());
    btScalar outside = -1;
    for (int axis = 0; axis < 3; ++axis) outside = btMax(outside, btFabs(local[axis]) - half[axis]);
    closest = btMin(closest, outside);
  }
  EXPECT_LT(closest, btScalar(0.005)) << "the push should bring the plate to the node";
  EXPECT_GT(closest, btScalar(-0.001)) << "the pinned node ended a step inside the plate";
}

TEST(ToolKinds, RegisteringAfterThePairExistsReroutesIt) {
  SceneSettings settings;
  settings.algorithm = Algorithm::ThinTool;
  SoftBallScene scene(settings);
  scene.settle();
  // From just above the skin, 5 mm a step, so that contact builds up gently and stays.
  btTransform pose(btQuaternion::getIdentity(), btVector3(0, btScalar(scene.ballTop() + 0.06), 0));
  auto pressFurther = [&] {
    pose.getOrigin().setY(pose.getOrigin().y() - btScalar(0.005));
    scene.step(pose);
  };
  for (int i = 0; i < 6; ++i) pressFurther();
  ASSERT_GT(scene.tool()->report().diagnostics.detection.colliding, 0u);
  ASSERT_TRUE(thintool::removeTool(scene.world(), scene.toolBody()));
  pressFurther();  // the stock handler's step
  Tool& again = thintool::addTool(scene.world(), scene.toolBody());
  pressFurther();
  EXPECT_GT(again.report().diagnostics.detection.colliding, 0u);
}

TEST(ToolKinds, ATeleportedToolDoesNotFlingTheTissue) {
  // The tool waits 50 m above the ball while it settles, then jumps onto it in one step: Bullet
  // derives a velocity of kilometres per second from that jump, which must not reach the nodes.
  SceneSettings settings;
  SoftBallScene scene(settings);
  scene.settle();
  scene.step(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(scene.ballTop() - 0.005), 0)));
  const ToolDiagnostics& d = scene.tool()->report().diagnostics;
  EXPECT_GT(d.detection.colliding, 0u);
  const btSoftBody& ball = scene.ball();
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    EXPECT_LT(ball.m_nodes[i].m_x.length(), 5) << "node " << i;
  }
}

// A cloth laid on a kinematic plate registered as a tool: once it rests, the plate's report carries
// its weight, the response's and the soft solver's holds' together (the clamp's test has a grasp,
// where the holds carry most of it).
TEST(ToolKinds, AToolCarriesTheWeightOfAClothRestingOnIt) {
  SoftWorld soft;
  btBoxShape plateShape(btVector3(1, btScalar(0.01), 1));
  btDefaultMotionState plateMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &plateMotion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  plate.setActivationState(DISABLE_DEACTIVATION);
  soft.world.addRigidBody(&plate);
  Tool& tool = addTool(soft.world, plate);
  const btScalar h = btScalar(0.08);
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(soft.world.getWorldInfo(), btVector3(-0.5, h, -0.5),
                                                     btVector3(0.5, h, -0.5), btVector3(-0.5, h, 0.5),
                                                     btVector3(0.5, h, 0.5), 9, 9, 0, true);
  cloth->getCollisionShape()->setMargin(btScalar(0.02));
  cloth->setTotalMass(2);
  soft.world.addSoftBody(cloth);
  const double weight = 2 * 10;
  double carried = 0;
  int steps = 0;
  for (int i = 0; i < 240; ++i) {
    soft.world.stepSimulation(btScalar(1.0 / 120), 1, btScalar(1.0 / 120));
    const ToolStepReport& report = tool.report();
    EXPECT_TRUE(isFinite(report.holdWrench.force) && isFinite(report.holdWrench.torque));
    if (i >= 180) {  // resting for the last half second
      carried += report.wrench.force.y + report.holdWrench.force.y;
      ++steps;
    }
  }
  EXPECT_NEAR(carried / steps, -weight, 0.05 * weight) << "the cloth presses down on the plate";
  soft.world.removeSoftBody(cloth);
  delete cloth;
  removeTool(soft.world, plate);
  soft.world.removeRigidBody(&plate);
}

// Bullet's own soft solver applies the holds too, but no one measures them there.
TEST(ToolKinds, WithBulletsSoftSolverTheHoldsLoadIsNotMeasured) {
  CollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, -10, 0));
  world.getWorldInfo().m_gravity = btVector3(0, -10, 0);
  btBoxShape plateShape(btVector3(1, btScalar(0.01), 1));
  btDefaultMotionState plateMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &plateMotion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  world.addRigidBody(&plate);
  Tool& tool = addTool(world, plate);
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-0.5, 0.05f, -0.5),
                                                     btVector3(0.5, 0.05f, -0.5), btVector3(-0.5, 0.05f, 0.5),
                                                     btVector3(0.5, 0.05f, 0.5), 9, 9, 0, true);
  cloth->getCollisionShape()->setMargin(btScalar(0.02));
  cloth->setTotalMass(2);
  world.addSoftBody(cloth);
  double moved = 0;
  for (int i = 0; i < 60; ++i) {
    world.stepSimulation(btScalar(1.0 / 120), 1, btScalar(1.0 / 120));
    const ToolStepReport& report = tool.report();
    moved += double(report.diagnostics.nodesMoved);
    EXPECT_EQ(report.holdWrench.force, Vec3{});
  }
  EXPECT_GT(moved, 0) << "the tool held the cloth";
  world.removeSoftBody(cloth);
  delete cloth;
  removeTool(world, plate);
  world.removeRigidBody(&plate);
}

}  // namespace
}  // namespace thintool::scenes
