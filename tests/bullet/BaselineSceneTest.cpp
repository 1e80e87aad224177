// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The team's baseline scene (shared/notes/baseline.md) with a realistic skin: soft margin 0.05, and
// the paper's algorithm as published (discrete detection; the swept default has its own matrix).
// ThinTool must neither let a node through the plate nor end with the plate inside the ball in
// every case where the plate moves less than its own thickness per step; stock Bullet, in the
// same test, shows the failure that makes the difference. Faster cases belong to swept detection.

#include "SoftBallScene.h"

#include <gtest/gtest.h>

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
  EXPECT_LT(r.metrics.maxPenetration, 0.01) << "no node past the mid-plane";
  EXPECT_GT(r.maxContacts, 0) << "the plate did press the ball";
}

INSTANTIATE_TEST_SUITE_P(SlowCases, ThinToolPlate,
                         ::testing::Values(Case{0.1, 60}, Case{1, 60}, Case{0.1, 1000}, Case{1, 1000},
                                           Case{5, 1000}, Case{20, 1000}),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return "speed" + std::to_string(int(param.param.speed * 10)) + "dm_per_s_dt1_" +
                                  std::to_string(int(param.param.stepsPerSecond));
                         });

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
