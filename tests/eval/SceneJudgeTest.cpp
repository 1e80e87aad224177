// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <SceneJudge.h>

#include <gtest/gtest.h>

namespace thintool::eval {
namespace {

RunResult runWithSpeeds(double node, double tool) {
  RunResult run;
  run.finite = true;
  run.peakNodeSpeed = node;
  run.peakToolSpeed = tool;
  return run;
}

TEST(SceneJudge, EnergyFailsOnlyPastTheToolsShareAndTwiceTheBodyWithoutTheTool) {
  // A tool at 1 m/s may bring nodes to 20 × 1 + 20 = 40 m/s.
  EXPECT_FALSE(judge(runWithSpeeds(39, 1)).failed);
  EXPECT_TRUE(judge(runWithSpeeds(100, 1)).energy);
  // A body that shakes at 60 m/s without any tool: 100 m/s is not the tool's doing, 130 is.
  EXPECT_FALSE(judge(runWithSpeeds(100, 1), 60).failed);
  const Verdict verdict = judge(runWithSpeeds(130, 1), 60);
  EXPECT_TRUE(verdict.energy);
  EXPECT_NE(joinReasons(verdict).find("60 m/s without the tool"), std::string::npos) << joinReasons(verdict);
  // The control never forgives what the tool's own speed does not.
  EXPECT_TRUE(judge(runWithSpeeds(100, 1), 0).energy);
}

}  // namespace
}  // namespace thintool::eval
