// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Swept detection where the paper's discrete detection cannot follow: a tool that jumps through a
// thin sheet in one step, a fast swipe across the ball, a tool reversed and pulled out while inside.

#include "Metrics.h"
#include "SoftBallScene.h"
#include "SoftWorld.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace thintool::scenes {
namespace {

// A 1 × 1 m sheet pinned at its corners at y = 1, and a 0.3 m plate, 2 cm thick, pushed down
// through it at 10 m/s: at 60 Hz it goes from 9 cm above the sheet to 8 cm below it in one step,
// then on for 0.25 m and holds. Returns how many sheet nodes under the plate's footprint end
// above its underside (the plate went through them).
int sheetNodesLeftAbove(bool swept) {
  SoftWorld soft(btVector3(0, 0, 0));
  btSoftRigidDynamicsWorld& world = soft.world;
  btSoftBody* sheet = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-0.5, 1, -0.5),
                                                     btVector3(0.5, 1, -0.5), btVector3(-0.5, 1, 0.5),
                                                     btVector3(0.5, 1, 0.5), 11, 11, 1 + 2 + 4 + 8, true);
  sheet->getCollisionShape()->setMargin(0.01);
  sheet->setTotalMass(0.1);
  world.addSoftBody(sheet);

  btBoxShape plateShape(btVector3(0.15, 0.01, 0.15));
  btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.1, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  world.addRigidBody(&plate);
  ToolOptions options;
  options.swept = swept;
  addTool(world, plate, options);

  const btScalar dt = btScalar(1) / 60;
  constexpr btScalar kStart = 1.1, kEnd = 0.75, kSpeed = 10;
  btScalar y = kStart;
  for (int step = 0; step < 20; ++step) {
    y = btMax(kEnd, kStart - kSpeed * dt * btScalar(step));
    motion.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, y, 0)));
    world.stepSimulation(dt, 1, dt);
  }
  int above = 0;
  for (int i = 0; i < sheet->m_nodes.size(); ++i) {
    const btVector3& x = sheet->m_nodes[i].m_x;
    above += std::abs(x.x()) < 0.15 && std::abs(x.z()) < 0.15 && x.y() > y - 0.01;
  }
  removeTool(world, plate);
  world.removeRigidBody(&plate);
  world.removeSoftBody(sheet);
  delete sheet;
  return above;
}

TEST(SweptCases, AToolThatJumpsThroughAThinSheetInOneStepIsCaught) {
  EXPECT_EQ(sheetNodesLeftAbove(true), 0) << "the sheet is carried down, on the side it was on";
  EXPECT_GT(sheetNodesLeftAbove(false), 0) << "the discrete algorithm misses it: the test proves the difference";
}

// A free 0.2 × 0.2 m sheet thrown up at 15 m/s at a still 0.3 m plate 10 cm above it: at 60 Hz it
// goes from 9 cm below the plate's underside to 14 cm above its top in one step, where nothing of
// it was near the plate the step before. Smaller than the plate, it has no way round it. Returns the
// crossings of the plate's mid-plane in its footprint, and the sheet's highest node at the end.
RunMetrics thrownSheet(btScalar& outHighest) {
  SoftWorld soft(btVector3(0, 0, 0));
  btSoftRigidDynamicsWorld& world = soft.world;
  btSoftBody* sheet = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-0.1, 1, -0.1),
                                                     btVector3(0.1, 1, -0.1), btVector3(-0.1, 1, 0.1),
                                                     btVector3(0.1, 1, 0.1), 5, 5, 0, true);
  sheet->getCollisionShape()->setMargin(0.01);
  sheet->setTotalMass(0.02);
  world.addSoftBody(sheet);

  btBoxShape plateShape(btVector3(0.15, 0.01, 0.15));
  btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.1, 0)));
  btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &plateShape));
  plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  world.addRigidBody(&plate);
  addTool(world, plate, ToolOptions{});

  ToolBox box;
  box.origin = {0, 1.1, 0};
  box.halfExtents = {0.15, 0.01, 0.15};
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < sheet->m_faces.size(); ++i) {
    faces.push_back({static_cast<int>(sheet->m_faces[i].m_n[0] - &sheet->m_nodes[0]),
                     static_cast<int>(sheet->m_faces[i].m_n[1] - &sheet->m_nodes[0]),
                     static_cast<int>(sheet->m_faces[i].m_n[2] - &sheet->m_nodes[0])});
  }
  const btScalar dt = btScalar(1) / 60;
  world.stepSimulation(dt, 1, dt);  // at rest: nothing near the plate
  CrossingTracker tracker;
  tracker.start(box, nodePositions(*sheet), 0);
  sheet->setVelocity(btVector3(0, 15, 0));
  for (int step = 0; step < 10; ++step) {
    world.stepSimulation(dt, 1, dt);
    tracker.update(box, nodePositions(*sheet), faces);
  }
  outHighest = -BT_LARGE_FLOAT;
  for (int i = 0; i < sheet->m_nodes.size(); ++i) {
    outHighest = btMax(outHighest, sheet->m_nodes[i].m_x.y());
  }
  removeTool(world, plate);
  world.removeRigidBody(&plate);
  world.removeSoftBody(sheet);
  delete sheet;
  return tracker.metrics();
}

TEST(SweptCases, ASheetThrownThroughAStillToolInOneStepIsCaught) {
  btScalar highest = 0;
  const RunMetrics m = thrownSheet(highest);
  EXPECT_EQ(m.crossed, 0);
  EXPECT_LT(highest, 1.09) << "the sheet stops under the plate";
}

TEST(SweptCases, AFastSwipeAcrossTheBallKeepsEveryNodeUnderThePlate) {
  // Pressed 5 cm into the top of the ball, the plate swipes 3 m sideways at 20 m/s.
  SceneSettings settings;
  SoftBallScene scene(settings);
  scene.settle();
  const double height = scene.ballTop() - 0.05;
  constexpr double kSpeed = 20;
  const RunMetrics m = runTrajectory(scene, 60, [&](int step) {
    const double x = std::min(-1.5 + kSpeed * step / 60.0, 1.5);
    return btTransform(btQuaternion::getIdentity(), btVector3(btScalar(x), btScalar(height), 0));
  });
  EXPECT_EQ(m.crossed, 0);
  EXPECT_FALSE(m.everInside);
}

TEST(SweptCases, ReversedAndPulledOutWhileInsideEveryNodeStaysOnItsSide) {
  // In at 5 m/s to the ball's mean height, then out at 20 m/s back to 1 m above the ball.
  SceneSettings settings;
  SoftBallScene scene(settings);
  scene.settle();
  const double top = scene.ballTop() + 0.2;
  const double bottom = scene.ballMeanHeight();
  const int inSteps = static_cast<int>(std::ceil((top - bottom) / (5.0 / 60)));
  const RunMetrics m = runTrajectory(scene, inSteps + 12, [&](int step) {
    const double y = step <= inSteps ? top - (top - bottom) * step / inSteps
                                     : std::min(bottom + 20.0 * (step - inSteps) / 60, top + 1);
    return btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(y), 0));
  });
  EXPECT_EQ(m.crossed, 0);
  EXPECT_EQ(m.stillCrossed, 0);
  EXPECT_FALSE(m.everInside);
}

}  // namespace
}  // namespace thintool::scenes
