// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The team's baseline scene (shared/notes/baseline.md) with a realistic skin: soft margin 0.05, and
// the paper's algorithm as published (discrete detection; the swept default has its own matrix).
// ThinTool must neither let a node through the plate nor end with the plate inside the ball in
// the cases where the plate moves less than its own thickness per step, but one (PaperPlate); stock
// Bullet, in the same test, shows the failure that makes the difference. Faster cases belong to
// swept detection. Judged by the evaluation suite's ground truth (scenes/Metrics.h).

#include "SoftBallScene.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace thintool::scenes {
namespace {

PressResult press(Algorithm algorithm, ToolShape tool, double speed, double stepsPerSecond) {
  PressSettings settings;
  settings.scene.algorithm = algorithm;
  settings.scene.tool = tool;
  settings.scene.timeStep = 1 / stepsPerSecond;
  settings.speed = speed;
  return runPress(settings);
}

struct Case {
  double speed;
  double stepsPerSecond;
};

class ThinToolPlate : public ::testing::TestWithParam<Case> {};

TEST_P(ThinToolPlate, NoNodeCrossesAndThePlateNeverEndsAStepInsideTheBall) {
  const Case c = GetParam();
  ASSERT_LE(c.speed / c.stepsPerSecond, 0.02) << "a slow case: at most the plate's thickness per step";
  const PressResult r = press(Algorithm::ThinToolPaper, ToolShape::Plate, c.speed, c.stepsPerSecond);
  EXPECT_EQ(r.metrics.crossed, 0);
  EXPECT_FALSE(r.metrics.everInside);
  EXPECT_GT(r.maxContacts, 0) << "the plate did press the ball";
}

INSTANTIATE_TEST_SUITE_P(SlowCases, ThinToolPlate,
                         ::testing::Values(Case{0.1, 60}, Case{0.1, 1000}, Case{1, 1000}, Case{5, 1000},
                                           Case{20, 1000}),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return "speed" + std::to_string(int(param.param.speed * 10)) + "dm_per_s_dt1_" +
                                  std::to_string(int(param.param.stepsPerSecond));
                         });

// At 1 m/s and 1/60 s the plate moves 17 mm a step, under its thickness, and in Bullet's float
// build the paper's algorithm still lets one node through: the ball bulges up beside the rim, and
// Bullet's solve moves a node from there, 3 cm above the plate and 2.7 cm beyond its rim, to under
// it in one step, across the rim's corner. The swept default holds the case; the paper's count is
// printed, not asserted, since where such a node goes differs between Bullet's two builds.
TEST(PaperPlate, TheDefaultHoldsTheCaseWhereThePaperLetsANodeAcrossTheRim) {
  const PressResult paper = press(Algorithm::ThinToolPaper, ToolShape::Plate, 1, 60);
  std::printf("the paper's algorithm at 1 m/s and 1/60 s: %d nodes crossed, %d steps with a face pierced\n",
              paper.metrics.crossed, paper.metrics.piercedSteps);
  const PressResult swept = press(Algorithm::ThinTool, ToolShape::Plate, 1, 60);
  EXPECT_GT(swept.maxContacts, 0) << "the plate did press the ball";
  EXPECT_EQ(swept.metrics.crossed, 0);
  EXPECT_EQ(swept.metrics.piercedSteps, 0);
  EXPECT_FALSE(swept.metrics.everInside);
  EXPECT_LT(swept.metrics.maxPenetration, 1e-4);
}

// The same press in PyBullet's soft world, btSoftMultiBodyDynamicsWorld: stock Bullet lets the plate
// through there too, and ThinTool's defaults hold it.
TEST(SoftMultiBodyWorld, ThinToolHoldsThePressThatStockLetsThrough) {
  PressSettings settings;
  settings.scene.world = WorldKind::SoftMultiBody;
  settings.scene.algorithm = Algorithm::StockE;
  const PressResult stock = runPress(settings);
  EXPECT_GT(stock.metrics.crossed, 0);
  settings.scene.algorithm = Algorithm::ThinTool;
  const PressResult thin = runPress(settings);
  EXPECT_GT(thin.maxContacts, 0) << "the plate did press the ball";
  EXPECT_EQ(thin.metrics.crossed, 0);
  EXPECT_EQ(thin.metrics.piercedSteps, 0);
  EXPECT_FALSE(thin.metrics.everInside);
  EXPECT_LT(thin.metrics.maxPenetration, 1e-4);
}

// And in Bullet's deformable world (a mass-spring ball, Bullet's implicit solve with its own rigid
// contacts inside it): the plate pressed at 8 m/s leaves faces pierced with stock; ThinTool's
// DeformableBodySolver, whose last word follows the solve, holds it.
// The plate pressed at 8 m/s into a mass-spring ball in Bullet's deformable world.
PressSettings deformablePress(Algorithm algorithm) {
  PressSettings settings;
  settings.scene.world = WorldKind::Deformable;
  settings.speed = 8;
  settings.scene.algorithm = algorithm;
  return settings;
}

TEST(DeformableWorld, ThinToolsLastWordHoldsThePressThatStockLetsThrough) {
  PressSettings settings = deformablePress(Algorithm::StockE);
  const PressResult stock = runPress(settings);
  EXPECT_GT(stock.metrics.piercedSteps, 0);
  EXPECT_GT(stock.metrics.maxPenetration, 1e-3);
  settings.scene.algorithm = Algorithm::ThinTool;
  const PressResult thin = runPress(settings);
  EXPECT_EQ(thin.metrics.crossed, 0);
  EXPECT_EQ(thin.metrics.piercedSteps, 0);
  EXPECT_FALSE(thin.metrics.everInside);
  EXPECT_LT(thin.metrics.maxPenetration, 1e-4);
}

// With ThinTool's node contacts in Bullet's deformable solve (BulletSettings::deformableNodeContacts,
// the default) in place of Bullet's own, the press holds all the same.
TEST(DeformableWorld, ThinToolsNodeContactsInBulletsSolveHoldThePress) {
  PressSettings settings = deformablePress(Algorithm::ThinTool);
  const PressResult thinToolsContacts = runPress(settings);
  settings.scene.toolOptions.bullet.deformableNodeContacts = false;
  const PressResult bulletsContacts = runPress(settings);
  std::printf("the last word's moves: %ld with Bullet's node contacts, %ld with ThinTool's (%ld of them)\n",
              bulletsContacts.lastWordMoves, thinToolsContacts.lastWordMoves,
              thinToolsContacts.deformableNodeContacts);
  EXPECT_EQ(bulletsContacts.deformableNodeContacts, 0);
  EXPECT_GT(thinToolsContacts.deformableNodeContacts, 0) << "ThinTool's contacts went into the solve";
  EXPECT_EQ(thinToolsContacts.metrics.crossed, 0);
  EXPECT_EQ(thinToolsContacts.metrics.piercedSteps, 0);
  EXPECT_FALSE(thinToolsContacts.metrics.everInside);
  EXPECT_LT(thinToolsContacts.metrics.maxPenetration, 1e-4);
}

TEST(StockPlate, FailsAtOneMetrePerSecondAndSixtyHertz) {
  // The realistic-skin stock set-up (E) and the defaults (A) both let the plate through.
  for (Algorithm stock : {Algorithm::StockE, Algorithm::StockA}) {
    const PressResult r = press(stock, ToolShape::Plate, 1, 60);
    EXPECT_GT(r.metrics.crossed, 0) << algorithmName(stock);
    EXPECT_TRUE(r.metrics.endsInside) << algorithmName(stock);
  }
}

TEST(Needle, IsCaughtWhereStockBulletMissesIt) {
  const PressResult thin = press(Algorithm::ThinToolPaper, ToolShape::Needle, 0.1, 1000);
  EXPECT_GT(thin.maxContacts, 0);
  EXPECT_FALSE(thin.metrics.everInside);
  EXPECT_EQ(thin.metrics.crossed, 0);

  const PressResult stock = press(Algorithm::StockE, ToolShape::Needle, 0.1, 1000);
  EXPECT_TRUE(stock.metrics.endsInside) << "baseline.md: the bar slips between the ball's nodes";
}

}  // namespace
}  // namespace thintool::scenes
