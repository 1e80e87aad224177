// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Swept detection (the default) on the team's baseline scene with a realistic skin (soft margin
// 0.05): plate and needle, speeds 0.1 to 50 m/s, steps 1/30 to 1/1000 s; the full matrix.
//
// No node crosses the tool, and it never ends a step inside the ball, up to 0.83 m a step. In the
// fastest case, 50 m/s at 1/30 s, the tool moves 1.67 m a step into a ball of radius 1 and crushes
// it to its centre in one step; no node crosses it either, but in Bullet's float build the ball,
// rebounding during the hold, wraps round the tool (plate and needle) and closes over it for one
// step of the eight, no node having passed through it; it is open again at the end.

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

class SweptMatrix : public ::testing::TestWithParam<Case> {};

TEST_P(SweptMatrix, NoNodeThroughTheToolAndNotLeftInsideTheBall) {
  const Case c = GetParam();
  PressSettings settings;
  settings.scene.algorithm = Algorithm::ThinTool;
  settings.scene.tool = c.tool;
  settings.scene.timeStep = 1 / c.stepsPerSecond;
  settings.speed = c.speed;
  const PressResult r = runPress(settings);
  EXPECT_EQ(r.metrics.crossed, 0);
  EXPECT_FALSE(r.metrics.endsInside);
  EXPECT_LE(r.metrics.insideSteps, c.speed / c.stepsPerSecond > 1 ? 1 : 0);
  EXPECT_GT(r.maxContacts, 0) << "the tool did press the ball";
}

std::vector<Case> matrix() {
  std::vector<Case> cases;
  for (ToolShape tool : {ToolShape::Plate, ToolShape::Needle}) {
    for (double rate : {30.0, 60.0, 240.0, 1000.0}) {
      for (double speed : {0.1, 1.0, 5.0, 20.0, 50.0}) {
        cases.push_back({tool, speed, rate});
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
