// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The runner on the shipped scenes: the ground truth tells stock Bullet's and the paper's
// failures from the swept detection's success, with the time per step beside them.

#include <Runner.h>
#include <SceneGenerator.h>

#include <gtest/gtest.h>

#include <cmath>

namespace thintool::eval {
namespace {

const std::string kScenes = THINTOOL_EVAL_SCENES;

RunResult run(const std::string& file, const std::vector<std::string>& overrides) {
  std::vector<Override> parsed;
  for (const std::string& o : overrides) parsed.push_back(parseOverride(o));
  return runScene(loadScene(kScenes + "/" + file, parsed));
}

TEST(Runner, ThePlatePressTellsStockFromSwept) {
  const RunResult stock = run("plate_press.json", {"algorithm=stock-E", "tools[0].trajectory.speed=5"});
  const RunResult swept = run("plate_press.json", {"algorithm=swept", "tools[0].trajectory.speed=5"});
  EXPECT_GT(stock.truth.crossedNodes, 0);
  EXPECT_GT(stock.truth.toolInsideSteps, 0);
  EXPECT_EQ(swept.truth.crossedNodes, 0);
  EXPECT_EQ(swept.truth.toolInsideSteps, 0);
  EXPECT_EQ(swept.truth.maxPenetration, 0);
  for (const RunResult* r : {&stock, &swept}) {
    EXPECT_EQ(r->softFaces, 128);
    EXPECT_TRUE(r->finite);
    EXPECT_GT(r->microsecondsPerStep, 0);
    EXPECT_EQ(std::size_t(r->truth.steps), r->samples.size());
  }
  EXPECT_EQ(stock.toolNodes, 0);
  EXPECT_GT(swept.toolNodes, 100);
  EXPECT_GT(swept.toolMicrosecondsPerStep, 0);
  EXPECT_LT(swept.toolMicrosecondsPerStep, swept.microsecondsPerStep);
}

TEST(Runner, TheSheetIsPiercedByThePaperAndCaughtBySweptDetectionOrTheLastWord) {
  const RunResult paper = run("sheet_pierce.json", {"algorithm=paper"});
  const RunResult swept = run("sheet_pierce.json", {"algorithm=swept"});
  // The paper's detection with the last word after Bullet's solve.
  const RunResult discrete = run("sheet_pierce.json", {"algorithm=discrete"});
  EXPECT_GT(paper.truth.crossedNodes, 0);
  EXPECT_GT(paper.truth.stillCrossed, 0);
  EXPECT_EQ(swept.truth.crossedNodes, 0);
  EXPECT_EQ(discrete.truth.crossedNodes, 0);
  EXPECT_EQ(discrete.truth.piercedSteps, 0);
}

TEST(Runner, AToolsStepIsMeasuredAgainstItsThickness) {
  // The plate is 20 mm thick and goes straight down: at 1 m/s and 1/60 s it moves 16.7 mm a step,
  // at 2 m/s 33.3 mm.
  for (const double speed : {1.0, 2.0}) {
    const RunResult result = run("plate_press.json", {"tools[0].trajectory.speed=" + std::to_string(speed)});
    // Poses come back from Bullet's float build: to about a millionth.
    EXPECT_NEAR(result.peakToolStepOverThickness, speed / 60 / 0.02, 1e-4) << speed << " m/s";
  }
}

TEST(Runner, TheForceErrorIsZeroAgainstItselfAndNaNWithoutAForce) {
  const RunResult coarse = run("plate_press.json", {"thintool.force=true", "tools[0].trajectory.speed=2"});
  const RunResult fine = run("plate_press.json", {"thintool.force=true", "tools[0].trajectory.speed=2", "step.dt=1/240"});
  const RunResult stock = run("plate_press.json", {"algorithm=stock-E", "tools[0].trajectory.speed=2"});
  ASSERT_GT(coarse.peakForce, 0);
  EXPECT_EQ(forceError(coarse, coarse), 0);
  const double error = forceError(coarse, fine);
  EXPECT_GT(error, 0);
  EXPECT_LT(error, 1);
  EXPECT_TRUE(std::isnan(forceError(stock, fine)));
}

TEST(Runner, EveryShippedSceneRunsWithItsOwnAlgorithm) {
  for (const char* file : {"clamp_grasp.json", "needle_press.json", "blade_angle.json", "vessel_press.json"}) {
    SCOPED_TRACE(file);
    const RunResult result = run(file, {"step.duration=0.5"});
    EXPECT_TRUE(result.finite);
    EXPECT_EQ(result.truth.crossedNodes, 0);
    EXPECT_EQ(result.truth.toolInsideSteps, 0);
    EXPECT_GT(result.softFaces, 0);
  }
}

TEST(Runner, TheExactHullBallHasTwiceResolutionPlusTwoFaces) {
  const RunResult result =
      run("plate_press.json", {"soft.exact_hull=true", "soft.resolution=255", "step.settle=0", "step.duration=0.05"});
  EXPECT_EQ(result.softFaces, 512);
  EXPECT_EQ(result.softNodes, 258);
}

TEST(Runner, AStartClearanceStartsEveryAlgorithmAboveItsOwnSettledBody) {
  // Stock A's 0.25 m margin lifts the settled ball above a start height fixed for stock E's 0.05 m.
  for (const char* algorithm : {"algorithm=stock-A", "algorithm=swept"}) {
    SCOPED_TRACE(algorithm);
    const RunResult result = run("plate_press.json", {algorithm, "tools[0].trajectory.speed=0.5", "step.duration=0.1"});
    ASSERT_FALSE(result.samples.empty());
    EXPECT_FALSE(result.samples.front().toolInside);
    EXPECT_EQ(result.truth.toolInsideSteps, 0);
    EXPECT_EQ(result.truth.maxPenetration, 0);
  }
}

TEST(Runner, TheBodySettlesAloneWhateverItsTools) {
  // The tools wait far above while the body settles, so what the settle shows (a body that its own
  // solver shakes) is the body's alone: the same with the tools as without them.
  for (const char* algorithm : {"algorithm=swept", "algorithm=stock-E"}) {
    SCOPED_TRACE(algorithm);
    std::vector<Override> overrides{parseOverride(algorithm), parseOverride("step.settle=0.5"),
                                    parseOverride("step.duration=0.05")};
    SceneSpec scene = loadScene(kScenes + "/plate_press.json", overrides);
    const RunResult withTools = runScene(scene);
    scene.tools.clear();
    const RunResult alone = runScene(scene);
    EXPECT_GT(withTools.settleNodeSpeed, 0);  // the ball falls onto the ground as it settles
    EXPECT_TRUE(std::isfinite(withTools.settleNodeSpeed));
    EXPECT_EQ(withTools.settleNodeSpeed, alone.settleNodeSpeed);
  }
}

TEST(Runner, ADynamicToolIsLaunchedAtItsPlannedSpeed) {
  // Generated seed 9098: a pressure ball planned about a metre tall settles 3.7 m tall, and the
  // needle's path, mapped onto the settled body, is stretched with it. The needle is launched
  // along that path at the speed it was planned with, and only after the step that puts it at its
  // start, which swept detection does not sweep.
  SceneSpec scene = generateScene(9098, kScenes);
  ASSERT_EQ(scene.tools.size(), 1u);
  ASSERT_GT(scene.tools[0].mass, 0);
  const std::vector<TrajectorySpec::Waypoint>& path = scene.tools[0].trajectory.waypoints;
  ASSERT_GE(path.size(), 2u);
  const double planned = length(path[1].position - path[0].position) / (path[1].time - path[0].time);
  scene.duration = scene.timeStep;
  const RunResult result = runScene(scene);
  EXPECT_GT(result.peakToolSpeed, 0.9 * planned);
  EXPECT_LT(result.peakToolSpeed, 1.1 * planned);
  EXPECT_EQ(result.truth.toolInsideSteps, 0);
}

TEST(Runner, ASheetIsCutOnceDuringTheRunAndJudgedToTheEnd) {
  // Generated seed 36 with Bullet's kinds: jaws through a sheet 16 nodes a side, cut 1.46 m long.
  GeneratorOptions kinds;
  kinds.bulletKinds = true;
  const SceneSpec scene = generateScene(36, kScenes, kinds);
  ASSERT_TRUE(scene.soft.cut);
  const RunResult result = runScene(scene);
  EXPECT_GT(result.linksCut, 0);
  EXPECT_TRUE(result.finite);
  EXPECT_EQ(long(result.samples.size()), std::lround(scene.duration / scene.timeStep));
  // Without the cut, the same scene cuts nothing.
  SceneSpec uncut = scene;
  uncut.soft.cut.reset();
  EXPECT_EQ(runScene(uncut).linksCut, 0);
}

}  // namespace
}  // namespace thintool::eval
