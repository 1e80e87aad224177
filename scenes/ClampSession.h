// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The clamp under the hand (the paper's §IV.A set-up): a 3-DoF haptic device drives the clamp of
/// ClampScene.h through haptics::mapDeviceToClamp (two axes move it in its plane, the third opens
/// and closes it), and the haptic loop renders the load the jaws carry (HapticLoop::publishToolForce),
/// scaled down by the workspace as the coupling's force is. The clamp is kinematic and follows the
/// device exactly, so no coupling separates them. Physics at 60 Hz, the haptic loop at 1 kHz; in
/// lockstep (the loop's ticks of each step run before it, deterministic) or in real time (the
/// loop in its own thread). Not part of the library.

#include "ClampScene.h"

#include <thintool/haptics/ClampMapping.h>
#include <thintool/haptics/HapticLoop.h>

#include <functional>
#include <vector>

namespace thintool::scenes {

struct ClampSessionSample;

struct ClampSessionSettings {
  ClampBody body = ClampBody::Sphere;
  bool friction = true;
  double timeStep = 1.0 / 60;  ///< s, physics
  bool realTime = false;
  /// 1 kHz; the workspace's scale divides the rendered load, as it does the coupling's force.
  haptics::HapticLoopSettings loop = defaultLoop();
  /// The device's centre is the open clamp at its hinge; 20 world metres per device metre (a 5 cm
  /// lift at the grip lifts the clamp 1 m); pushing the grip away closes it, 30 rad per metre.
  haptics::ClampMapping mapping = defaultMapping();

  /// Called after every step (a viewer draws the world there); returning false ends the session.
  std::function<bool(const btSoftRigidDynamicsWorld&, Clamp&, const ClampSessionSample&, const haptics::HapticLoop&)>
      observer;

  static haptics::HapticLoopSettings defaultLoop();
  static haptics::ClampMapping defaultMapping();
};

struct ClampSessionSample {
  double time = 0;              ///< s, the step's end
  Vec3 device;                  ///< m, the device's point (its own frame)
  double opening = 0;           ///< rad
  double bodyCentreHeight = 0;  ///< m, mean node height
  Vec3 onClamp;                 ///< N, world: the body's force on the two jaws, from their reports
  Vec3 deviceForce;             ///< N, the force the loop last wrote to the device
  Vec3 bodyNetForce;            ///< N, Δp/dt − m·g of the body (ClampSample)
  Vec3 bodyPressure;            ///< N, the body's own pressure resultant (ClampSample)
};

struct ClampSessionResult {
  std::vector<ClampSessionSample> trace;
  haptics::LoopStatistics loop;
  double restCentreHeight = 0;  ///< m
  double bodyWeight = 0;        ///< N
  int crossed = 0;              ///< nodes through either jaw over the session
  bool jawEverInside = false;
  int steps = 0;
  double physicsMicrosecondsPerStep = 0;
};

/// Runs the session until the device ends (a recording's last row) or is lost.
ClampSessionResult runClampSession(const ClampSessionSettings& settings, haptics::Device& device);

/// A stretch in which the device stood still, measured from settle seconds after it began: what
/// the jaws carried and what the hand felt.
struct ClampSessionHold {
  double from = 0, to = 0;        ///< s
  double bodyCentreHeight = 0;    ///< m, mean
  Vec3 onClamp;                   ///< N, mean
  Vec3 deviceForce;               ///< N, mean
  double deviceForcePeakToPeak = 0;  ///< N, largest less smallest |device force|
  Vec3 bodyNetForce;              ///< N, mean
  Vec3 bodyPressure;              ///< N, mean
};

/// The stretches of at least settle + minimum seconds in which the device point moved less than
/// 1 µm from one sample to the next.
std::vector<ClampSessionHold> findHolds(const std::vector<ClampSessionSample>& trace, double settle = 0.2,
                                        double minimum = 0.1);

}  // namespace thintool::scenes
