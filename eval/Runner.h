// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Runs one scene file's scene in Bullet and measures it: accuracy by the ground truth
/// (GroundTruth.h), cost by the wall time of every stepSimulation call and ThinTool's own share of
/// it, from the same run. The ground truth is computed between steps and never timed.

#include "GroundTruth.h"
#include "SceneFile.h"

#include <WorldKind.h>

#include <functional>
#include <string>
#include <vector>

namespace thintool::eval {

struct StepSample {
  double time = 0;               ///< s after t = 0, at the step's end
  int crossings = 0;
  bool toolInside = false;
  bool selfIntersecting = false;  ///< inside by the winding number, but the surface passes through itself
  bool pinnedReached = false;    ///< not judged: a kinematic tool reached a pinned node (GroundTruthRun)
  double maxPenetration = 0;     ///< m
  int piercedFaces = 0;          ///< soft faces deeper than the ground truth's tolerance into a tool
  double nodeSpeed = 0;          ///< m/s, the fastest soft node this step
  double stepMicroseconds = 0;   ///< stepSimulation's wall time
  double toolMicroseconds = 0;   ///< ThinTool's detection, response and last word (0 for stock)
  Vec3 force;                    ///< N, the tissue's force on the tools (ThinTool with force on)
};

struct RunResult {
  std::string scene;
  AlgorithmKind algorithm = AlgorithmKind::Swept;
  double timeStep = 0;
  int softNodes = 0;
  int softFaces = 0;
  int toolNodes = 0;             ///< ThinTool's sample nodes over all tools (0 for stock)
  int linksCut = 0;              ///< by the scene's cut (SoftBodySpec::cut), each adding two nodes
  GroundTruthRun truth;
  double microsecondsPerStep = 0;
  double toolMicrosecondsPerStep = 0;
  double peakForce = 0;          ///< N, largest |force| of a step
  /// m/s, the fastest soft node over the measured steps: its displacement in a step over the step.
  double peakNodeSpeed = 0;
  /// m/s, the fastest soft node while the body settled, before any tool moved (the tools wait
  /// far above it then): how hard the body's own solver shook it.
  double settleNodeSpeed = 0;
  /// m/s, the fastest point of any tool over the measured steps: |v| + |ω|·reach, v and ω from the
  /// body's pose before and after the step (kinematic or dynamic alike), reach the farthest corner
  /// of its pieces from the body's origin.
  double peakToolSpeed = 0;
  /// The farthest any tool's fastest point went in a step, over that tool's thickness: the
  /// narrowest width of its thinnest piece across a face's normal. Under 1, every tool moved less
  /// than its own thickness in every measured step.
  double peakToolStepOverThickness = 0;
  bool finite = true;            ///< false when a soft node became non-finite (the run stops there)
  /// ThinTool's own count, over the run, of its writes that left Bullet's state not finite
  /// (ToolDiagnostics::nonFiniteWrites): not part of the verdict, which is the ground truth's.
  double nonFiniteWrites = 0;
  std::vector<StepSample> samples;
};

struct RunOptions {
  /// The Bullet world the scene is built in.
  scenes::WorldKind world = scenes::WorldKind::SoftRigid;
  /// Called after each step with (steps done, steps in all).
  std::function<void(int, int)> progress;
  /// Called once the soft body has settled, with its lowest and highest node heights (m).
  std::function<void(double, double)> settled;
};

/// Builds the scene's world, settles it, drives the tools through their trajectories and measures.
/// Throws thintool::Error for a scene ThinTool refuses (the message names the tool).
RunResult runScene(const SceneSpec& scene, const RunOptions& options = {});

/// The force error of a run against a reference run of the same scene (finest step and mesh): the
/// RMS over the reference's steps of |F(t) − F_ref(t)|, F linear between the run's steps, divided
/// by the reference's peak |F|. NaN when either run has no force (stock runs, force off).
double forceError(const RunResult& run, const RunResult& reference);

}  // namespace thintool::eval
