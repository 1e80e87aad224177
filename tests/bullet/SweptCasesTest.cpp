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

// A square sheet at y = 1, its corners pinned or free, under a kinematic 0.3 m plate, 2 cm thick,
// at y = 1.1, registered as a tool; all removed again on destruction.
struct SheetUnderPlate {
  SoftWorld soft{btVector3(0, 0, 0)};
  btSoftBody* sheet = nullptr;
  btBoxShape plateShape{btVector3(0.15, 0.01, 0.15)};
  btDefaultMotionState motion{btTransform(btQuaternion::getIdentity(), btVector3(0, 1.1, 0))};
  btRigidBody plate{btRigidBody::btRigidBodyConstructionInfo(0, &motion, &plateShape)};

  SheetUnderPlate(btScalar halfWidth, int nodesPerSide, bool pinned, btScalar mass, const ToolOptions& options) {
    const btScalar h = halfWidth;
    sheet = btSoftBodyHelpers::CreatePatch(soft.world.getWorldInfo(), btVector3(-h, 1, -h), btVector3(h, 1, -h),
                                           btVector3(-h, 1, h), btVector3(h, 1, h), nodesPerSide, nodesPerSide,
                                           pinned ? 1 + 2 + 4 + 8 : 0, true);
    sheet->getCollisionShape()->setMargin(0.01);
    sheet->setTotalMass(mass);
    soft.world.addSoftBody(sheet);
    plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    soft.world.addRigidBody(&plate);
    addTool(soft.world, plate, options);
  }
  ~SheetUnderPlate() {
    removeTool(soft.world, plate);
    soft.world.removeRigidBody(&plate);
    soft.world.removeSoftBody(sheet);
    delete sheet;
  }
  SheetUnderPlate(const SheetUnderPlate&) = delete;
  SheetUnderPlate& operator=(const SheetUnderPlate&) = delete;
};

// A 1 × 1 m sheet pinned at its corners, and the plate pushed down through it at 10 m/s: at 60 Hz it
// goes from 9 cm above the sheet to 8 cm below it in one step, then on for 0.25 m and holds.
// Returns how many sheet nodes under the plate's footprint end above its underside (the plate went
// through them).
int sheetNodesLeftAbove(bool swept) {
  ToolOptions options;
  options.swept = swept;
  options.separation.enabled = swept;  // the detections alone: the last word would catch it either way
  SheetUnderPlate scene(0.5, 11, true, 0.1, options);
  const btScalar dt = btScalar(1) / 60;
  constexpr btScalar kStart = 1.1, kEnd = 0.75, kSpeed = 10;
  btScalar y = kStart;
  for (int step = 0; step < 20; ++step) {
    y = btMax(kEnd, kStart - kSpeed * dt * btScalar(step));
    scene.motion.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, y, 0)));
    scene.soft.world.stepSimulation(dt, 1, dt);
  }
  int above = 0;
  for (int i = 0; i < scene.sheet->m_nodes.size(); ++i) {
    const btVector3& x = scene.sheet->m_nodes[i].m_x;
    above += std::abs(x.x()) < 0.15 && std::abs(x.z()) < 0.15 && x.y() > y - 0.01;
  }
  return above;
}

TEST(SweptCases, AToolThatJumpsThroughAThinSheetInOneStepIsCaught) {
  EXPECT_EQ(sheetNodesLeftAbove(true), 0) << "the sheet is carried down, on the side it was on";
  EXPECT_GT(sheetNodesLeftAbove(false), 0) << "the discrete detection misses it: the test proves the difference";
}

// A free 0.2 × 0.2 m sheet thrown up at 15 m/s at the plate standing still 10 cm above it: at 60 Hz
// it goes from 9 cm below the plate's underside to 14 cm above its top in one step, where nothing
// of it was near the plate the step before. Smaller than the plate, it has no way round it. Returns
// the crossings of the plate's mid-plane in its footprint, the sheet's highest node at the end, and
// whether the sheet got a face tree.
RunMetrics thrownSheet(const ToolOptions& options, btScalar& outHighest, bool& outFaceTree) {
  SheetUnderPlate scene(0.1, 5, false, 0.02, options);
  btSoftBody& sheet = *scene.sheet;
  ToolBox box;
  box.origin = {0, 1.1, 0};
  box.halfExtents = {0.15, 0.01, 0.15};
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < sheet.m_faces.size(); ++i) {
    faces.push_back({static_cast<int>(sheet.m_faces[i].m_n[0] - &sheet.m_nodes[0]),
                     static_cast<int>(sheet.m_faces[i].m_n[1] - &sheet.m_nodes[0]),
                     static_cast<int>(sheet.m_faces[i].m_n[2] - &sheet.m_nodes[0])});
  }
  const btScalar dt = btScalar(1) / 60;
  scene.soft.world.stepSimulation(dt, 1, dt);  // at rest: nothing near the plate
  BoxGroundTruth truth;
  truth.start(box, nodePositions(sheet), faces, false);
  sheet.setVelocity(btVector3(0, 15, 0));
  for (int step = 0; step < 10; ++step) {
    scene.soft.world.stepSimulation(dt, 1, dt);
    truth.update(box, nodePositions(sheet), faces);
  }
  outHighest = -BT_LARGE_FLOAT;
  for (int i = 0; i < sheet.m_nodes.size(); ++i) {
    outHighest = btMax(outHighest, sheet.m_nodes[i].m_x.y());
  }
  outFaceTree = !sheet.m_fdbvt.empty();
  return truth.metrics();
}

TEST(SweptCases, ASheetThrownThroughAStillToolInOneStepIsCaught) {
  btScalar highest = 0;
  bool faceTree = false;
  const RunMetrics m = thrownSheet(ToolOptions{}, highest, faceTree);
  EXPECT_EQ(m.crossed, 0);
  EXPECT_LT(highest, 1.09) << "the sheet stops under the plate";
  EXPECT_TRUE(faceTree) << "the gather walks the face tree it built";
}

TEST(SweptCases, ASheetThrownThroughAStillToolIsCaughtByTheScanOfItsFacesWithoutATree) {
  ToolOptions options;
  options.bullet.scanFaces = true;
  btScalar highest = 0;
  bool faceTree = true;
  const RunMetrics m = thrownSheet(options, highest, faceTree);
  EXPECT_EQ(m.crossed, 0);
  EXPECT_LT(highest, 1.09) << "the sheet stops under the plate";
  EXPECT_FALSE(faceTree) << "no face tree for Bullet to refit in every step";
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

// The sheet under the plate, the plate pressing it down at 0.5 m/s: once it has pressed 0.1 m, the
// gap the nodes under the middle of the plate keep from its underside, smallest and largest.
std::array<btScalar, 2> gapUnderPressingPlate(const ToolOptions& options) {
  SheetUnderPlate scene(0.5, 21, true, 0.1, options);
  const btScalar dt = btScalar(1) / 120;
  constexpr btScalar kStart = 1.1, kEnd = 0.9, kSpeed = 0.5;
  btScalar y = kStart;
  for (int step = 0; y > kEnd; ++step) {
    y = kStart - kSpeed * dt * btScalar(step);
    scene.motion.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, y, 0)));
    scene.soft.world.stepSimulation(dt, 1, dt);
  }
  std::array<btScalar, 2> gap{BT_LARGE_FLOAT, -BT_LARGE_FLOAT};
  for (int i = 0; i < scene.sheet->m_nodes.size(); ++i) {
    const btVector3& x = scene.sheet->m_nodes[i].m_x;
    if (std::abs(x.x()) > 0.06 || std::abs(x.z()) > 0.06) continue;
    const btScalar below = (y - 0.01) - x.y();
    gap[0] = btMin(gap[0], below);
    gap[1] = btMax(gap[1], below);
  }
  return gap;
}

TEST(Skin, AGivenSkinIsKeptInPlaceOfTheSoftBodysMargin) {
  const std::array<btScalar, 2> margin = gapUnderPressingPlate(ToolOptions{});  // the sheet's 0.01 m
  ToolOptions thicker;
  thicker.skin = 0.03;
  const std::array<btScalar, 2> given = gapUnderPressingPlate(thicker);
  EXPECT_NEAR(margin[0], 0.01, 0.004);
  EXPECT_NEAR(margin[1], 0.01, 0.004);
  EXPECT_NEAR(given[0], 0.03, 0.004);
  EXPECT_NEAR(given[1], 0.03, 0.004);
}

}  // namespace
}  // namespace thintool::scenes
