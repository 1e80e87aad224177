// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SceneJudge.h"

#include <algorithm>
#include <cstdio>

namespace thintool::eval {

namespace {

std::string format(const char* pattern, double a, double b = 0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

}  // namespace

Verdict judge(const RunResult& run, double controlNodeSpeed) {
  Verdict verdict;
  const GroundTruthRun& truth = run.truth;
  if (truth.crossedNodes > 0) {
    verdict.crossed = true;
    verdict.reasons.push_back(format("crossed %.0f nodes", truth.crossedNodes));
  }
  if (truth.toolInsideSteps > 0) {
    verdict.inside = true;
    verdict.reasons.push_back(format("tool inside in %.0f steps", truth.toolInsideSteps));
  }
  if (truth.piercedSteps > 0) {
    verdict.pierced = true;
    verdict.reasons.push_back(format("pierced faces in %.0f steps (up to %.0f at once)", truth.piercedSteps,
                                     truth.maxPiercedFaces));
  }
  if (truth.maxPenetration > kDeepPenetration) {
    verdict.deep = true;
    verdict.reasons.push_back(format("penetration %.3g mm", truth.maxPenetration * 1000));
  }
  if (!run.finite) {
    verdict.nonFinite = true;
    verdict.reasons.push_back(format("non-finite node after %.0f steps", double(run.samples.size())));
  }
  const double limit = kEnergySpeedFactor * std::max(run.peakToolSpeed, 1.0) + kEnergySpeedSlack;
  if (run.peakNodeSpeed > limit && run.peakNodeSpeed > kEnergyControlFactor * controlNodeSpeed) {
    verdict.energy = true;
    std::string reason = format("energy: a node at %.3g m/s, the tool at %.3g m/s", run.peakNodeSpeed, run.peakToolSpeed);
    if (controlNodeSpeed > 0) reason += format(", %.3g m/s without the tool", controlNodeSpeed);
    verdict.reasons.push_back(reason);
  }
  verdict.failed = !verdict.reasons.empty();
  verdict.pinnedReachedStep = truth.pinnedReachedStep;
  return verdict;
}

double controlNodeSpeed(const SceneSpec& scene, scenes::WorldKind world) {
  SceneSpec control = scene;
  control.tools.clear();
  RunOptions options;
  options.world = world;
  return runScene(control, options).peakNodeSpeed;
}

Verdict runAndJudge(const SceneSpec& scene, const RunOptions& options, RunResult* run) {
  RunResult local;
  RunResult& result = run != nullptr ? *run : local;
  result = runScene(scene, options);
  Verdict verdict = judge(result);
  if (verdict.energy) verdict = judge(result, controlNodeSpeed(scene, options.world));
  return verdict;
}

Verdict refusedVerdict(const std::string& message) {
  Verdict verdict;
  verdict.failed = true;
  verdict.refused = true;
  verdict.reasons.push_back("refused: " + message);
  return verdict;
}

std::string joinReasons(const Verdict& verdict) {
  std::string text;
  for (const std::string& reason : verdict.reasons) text += (text.empty() ? "" : "; ") + reason;
  return text;
}

}  // namespace thintool::eval
