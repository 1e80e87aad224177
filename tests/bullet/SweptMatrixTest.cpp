// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Swept detection (the default) on the team's baseline scene with a realistic skin (soft margin
// 0.05): plate and needle, speeds 0.1 to 50 m/s, steps 1/30 to 1/1000 s.
//
// Wherever the tool moves up to a third of the ball's radius in a step (0.33 m), no node crosses it
// and it never ends a step inside the ball. The matrix's three faster cases (20 m/s at 1/30 s,
// 50 m/s at 1/30 and 1/60 s: 0.67 to 1.67 m a step) crush the ball by up to a metre in one step;
// their outcome is chaotic, differs between Bullet's float and float64 builds, and is reported in
// README and docs/swept-matrix.md (scripts/swept-matrix.sh) rather than asserted here.

#include "SoftBallScene.h"

#include <gtest/gtest.h>

#include <string>

namespace thintool::scenes {
namespace {

struct Case {
  ToolShape tool;
  double speed;
  double stepsPerSecond;
};

constexpr double kBallRadius = 1;

class SweptMatrix : public ::testing::TestWithParam<Case> {};

TEST_P(SweptMatrix, NoNodeThroughTheToolAndNeverInsideTheBall) {
  const Case c = GetParam();
  PressSettings settings;
  settings.scene.algorithm = Algorithm::ThinTool;
  settings.scene.tool = c.tool;
  settings.scene.timeStep = 1 / c.stepsPerSecond;
  settings.speed = c.speed;
  const PressResult r = runPress(settings);
  EXPECT_EQ(r.metrics.crossed, 0);
  EXPECT_FALSE(r.metrics.everInside);
  EXPECT_GT(r.maxContacts, 0) << "the tool did press the ball";
}

std::vector<Case> matrix() {
  std::vector<Case> cases;
  for (ToolShape tool : {ToolShape::Plate, ToolShape::Needle}) {
    for (double rate : {30.0, 60.0, 240.0, 1000.0}) {
      for (double speed : {0.1, 1.0, 5.0, 20.0, 50.0}) {
        if (speed / rate <= kBallRadius / 3) {
          cases.push_back({tool, speed, rate});
        }
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(PlateAndNeedle, SweptMatrix, ::testing::ValuesIn(matrix()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return std::string(toolShapeName(param.param.tool)) + "_" +
                                  std::to_string(int(param.param.speed * 10)) + "dm_per_s_dt1_" +
                                  std::to_string(int(param.param.stepsPerSecond));
                         });

}  // namespace
}  // namespace thintool::scenes
