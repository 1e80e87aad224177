// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The stiff and extreme cases of the stability suite, as data: stiffness against time step for
/// the default response and for the paper's force response, extreme geometry, extreme motion and
/// broken soft meshes, each run in the paper's scene (SoftBallScene) and judged by the same
/// measures. Shared by tests/stability and examples/stability, which prints the table of
/// docs/results/stability.md.
///
/// A case is "stable" when no coordinate of the ball, of a dynamic tool or of ThinTool's report is
/// ever NaN or infinite, and the ball's kinetic energy does not grow while the tool holds still:
/// its largest value over the hold's last quarter stays below kEnergyTolerance times its largest
/// over the hold's first half, plus kEnergyFloor. (A squashed ball rings for about a second after a press, so the hold
/// lasts a second and the windows are far apart.)

#include "SoftBallScene.h"

#include <LinearMath/btTransform.h>

#include <functional>
#include <string>
#include <vector>

namespace thintool::scenes {

/// Kinetic energy (J) below which a held ball counts as at rest, for the energy-growth test: the
/// 1 kg ball at 1 m/s, the energy guard's resting speed (EnergyGuardSettings::restingSpeed). In
/// steps where the tool neither moves nor holds a node, the ball jitters on the ground by itself
/// up to about half a joule at 1/30 s (the needle-edge case's last quarter, 0.54 J, once the guard
/// had calmed its first half to 0.38 J); a blow-up reaches thousands.
constexpr double kEnergyFloor = 0.5;
/// The energy-growth test's allowance for a body that keeps moving at a steady energy (a coarse
/// ball rocking under the tool): the last quarter may reach this multiple of the first half.
constexpr double kEnergyTolerance = 1.1;

/// Contained cases: no soft node may end a step deeper than this inside the tool (m).
constexpr double kContainedDepth = 0.0005;

/// What a case's outcome must be: the test suite holds each case to it.
enum class Expectation {
  Contained,  ///< stable, no node through or inside the tool (kContainedDepth), the tool never inside the ball
  Stable,     ///< stable; crossings allowed (a response that does not aim to stop them)
  Finite,     ///< only finite: the suite shows the energy blowing up or not
  Rejected,   ///< registration fails with a thintool::Error that names the tool and the problem
};
const char* expectationName(Expectation expectation);

struct StressCase {
  std::string group;  ///< stiffness, geometry, motion, bad input
  std::string name;
  Expectation expectation = Expectation::Contained;
  SceneSettings scene;
  double speed = 1;           ///< m/s, the press's speed down to the ball's mean height
  double holdSeconds = 1;  ///< held at the bottom, the energy test's window
  /// Runs once the ball has settled, before the tool moves: breaks the mesh, say.
  std::function<void(SoftBallScene&)> prepare;
  /// Where the tool starts, instead of 0.1 m above the soft margin over the ball's top; it moves
  /// straight down from there until its origin is at the ball's mean height.
  std::function<btTransform(SoftBallScene&)> startPose;
  /// Changes the pose of the hold's first step (a teleport, a turn) given the pressed pose; the
  /// rest of the hold keeps the changed pose.
  std::function<btTransform(const btTransform& pressed, SoftBallScene&)> jump;
  /// > 0: the jump is a transient fault that lasts this many steps, then the pressed pose returns.
  int jumpSteps = 0;
};

struct StressOutcome {
  bool finite = true;         ///< every coordinate finite after every step
  bool energyBounded = true;  ///< see the file's comment
  double peakEnergy = 0;      ///< J, the ball's kinetic energy, largest after any step
  double holdEnergyFirst = 0; ///< J, largest over the hold's first half
  double holdEnergyLast = 0;  ///< J, largest over its last quarter
  RunMetrics metrics;         ///< crossings and penetration, measured from positions (Metrics.h)
  double deepestInside = 0;   ///< m, the deepest any soft node lay inside the tool at the end of a step
  long skippedFaces = 0;      ///< ThinTool's diagnostics summed over the steps
  long rejectedCorrections = 0;
  long invalidPosePairs = 0;
  int steps = 0;
  double microsecondsPerStep = 0;  ///< stepSimulation's mean wall time over the press and hold
  double peakForce = 0;       ///< N, the force model's net force, largest over the steps
  std::string error;          ///< registration's error message, when it failed
};

/// Every case of the suite, in the order of the stability table (docs/results/stability.md).
std::vector<StressCase> stressCases();

StressOutcome runStressCase(const StressCase& stressCase);

/// Whether outcome meets expectation; if not, why not.
bool meets(const StressOutcome& outcome, Expectation expectation, std::string* why = nullptr);

/// The ball's kinetic energy (J), movable nodes only.
double kineticEnergy(const btSoftBody& ball);

}  // namespace thintool::scenes
