// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The verdict on a run of a generated scene (SceneGenerator.h), from the ground truth and the
/// run's own measures alone. A run fails when any of these holds, each a reason of its own:
///
/// - crossed: a soft node passed through a tool (GroundTruthRun::crossedNodes > 0);
/// - inside: a tool's piece was inside the closed soft surface at the end of a step;
/// - pierced: a soft face reached deeper than the ground truth's tolerance into a tool at the end
///   of a step (GroundTruthRun::piercedSteps > 0);
/// - deep: a surface sample lay deeper than kDeepPenetration inside a tool;
/// - non-finite: a soft node's position became NaN or infinite (the run stops there);
/// - energy: a soft node moved faster than kEnergySpeedFactor × max(the fastest tool point,
///   1 m/s) + kEnergySpeedSlack in some step, and more than kEnergyControlFactor times as fast as
///   in the same scene run without its tools (the control, run only when the first test fails):
///   the tool put in more than it could, an explosion. Without the control, Bullet's own pressure
///   shaking a light body on the ground counted against a tool that never touched it;
/// - refused: ThinTool refused the scene (thintool::Error), with its message.
///
/// The geometric checks (crossed, inside, pierced, deep) cover the steps before a kinematic tool
/// reaches a pinned node, if one does (GroundTruthRun::pinnedReachedStep): from there no method
/// can keep the surface off the tool. Non-finite and energy cover every step.

#include "Runner.h"

#include <string>
#include <vector>

namespace thintool::eval {

/// m: the deepest a soft node or face centroid may lie inside a tool, the ground truth's piercing
/// tolerance (GroundTruth::kDefaultTolerance), 0.1 mm.
inline constexpr double kDeepPenetration = 1e-4;
/// The energy check: a node's speed above factor × max(tool speed, 1 m/s) + slack (m/s) fails.
/// A tool pushes nodes at its own speed; a contact's rebound and a stiff body's recoil add a few
/// times that, and settling under gravity some metres a second; twenty times is an explosion.
inline constexpr double kEnergySpeedFactor = 20;
inline constexpr double kEnergySpeedSlack = 20;  ///< m/s

/// The energy check's control: a node may move this many times as fast as in the scene without
/// its tools, whatever the tool's speed.
inline constexpr double kEnergyControlFactor = 2;

struct Verdict {
  bool failed = false;
  std::vector<std::string> reasons;  ///< one short text per failed check, with its number
  // Which checks failed, for the tallies.
  bool crossed = false;
  bool inside = false;
  bool pierced = false;
  bool deep = false;
  bool nonFinite = false;
  bool energy = false;
  bool refused = false;
  /// Not a failure: the step from which the geometric checks did not judge, or 0.
  int pinnedReachedStep = 0;
};

/// controlNodeSpeed: the peak node speed of the scene run without its tools (m/s), or 0 when not
/// measured (controlNodeSpeed below).
Verdict judge(const RunResult& run, double controlNodeSpeed = 0);

/// The energy check's control: the scene's peak node speed without its tools (m/s).
double controlNodeSpeed(const SceneSpec& scene, scenes::WorldKind world = scenes::WorldKind::SoftRigid);

/// Runs the scene and judges it, with the control run when the energy check asks for it. run, when
/// not null, receives the run.
Verdict runAndJudge(const SceneSpec& scene, const RunOptions& options = {}, RunResult* run = nullptr);
/// A scene ThinTool would not run: a failure with its message.
Verdict refusedVerdict(const std::string& message);

/// The reasons on one line, separated by "; ".
std::string joinReasons(const Verdict& verdict);

}  // namespace thintool::eval
