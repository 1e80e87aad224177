// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The paper's first case study driven by a haptic device: the spatula (the baseline plate) is a
/// dynamic body pulled by the virtual coupling towards the device's point, the tissue pushes it
/// back with the Hunt–Crossley force, and the device feels the coupling. Physics and haptic loop
/// both run at 1 kHz; as fast as possible (deterministic, the haptic tick and the physics step in
/// lockstep) or in real time (the haptic loop in its own thread).

#include "SoftBallScene.h"

#include <thintool/haptics/HapticLoop.h>

#include <vector>

namespace thintool::scenes {

struct HapticDemoSettings {
  bool realTime = false;
  double physicsRate = 1000;  ///< Hz
  haptics::HapticLoopSettings loop = defaultLoop();
  /// Where the device's origin sits above the settled ball's top (m, world).
  double originAboveTop = 0.15;
  /// kg, world. The hand feels it as toolMass · workspaceScale² (here 50 g), since the device
  /// moves workspaceScale times less for the same power.
  double toolMass = 0.0005;
  ToolOptions toolOptions = defaultToolOptions();

  static haptics::HapticLoopSettings defaultLoop();
  static ToolOptions defaultToolOptions();
};

struct HapticSample {
  double time = 0;             ///< s
  Vec3 device;                 ///< the device's point (world, m)
  Vec3 tool;                   ///< the tool's centre (world, m)
  Vec3 deviceForce;            ///< what the hand feels (N)
  Vec3 contactForce;           ///< the tissue's Hunt–Crossley force on the tool (world, N)
  double largestDeformation = 0;  ///< m, over the faces in contact
  int contacts = 0;
};

/// A stretch in which the device stood still with the tool in the tissue, and how steady the force
/// the hand felt was over it, from settle seconds after it began (the tissue's own transient).
struct HapticHold {
  double from = 0, to = 0;     ///< s, the stretch measured (after settling)
  double meanForce = 0;        ///< N, mean |device force|
  double peakToPeak = 0;       ///< N, largest less smallest |device force|
  double variation() const { return meanForce > 0 ? peakToPeak / meanForce : 0; }
};

/// The holds of a trace: the device point moved less than 1 µm (world) from one sample to the next
/// for at least settle + minimum seconds, and the tissue pushed the tool in at least a tenth of the
/// samples measured.
std::vector<HapticHold> findHolds(const std::vector<HapticSample>& trace, double settle = 0.2, double minimum = 0.1);

struct HapticDemoResult {
  std::vector<HapticSample> trace;
  haptics::LoopStatistics loop;
  RunMetrics metrics;  ///< crossings of the spatula, by the independent metrics
  double physicsMicrosecondsPerStep = 0;
  int steps = 0;
};

/// Runs the scene until the device ends (a recording's last row).
HapticDemoResult runHapticDemo(const HapticDemoSettings& settings, haptics::Device& device);

}  // namespace thintool::scenes
