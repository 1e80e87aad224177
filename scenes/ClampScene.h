// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The paper's second case study (§IV.A, Figs. 9, 10, 12): a clamp closes on a soft body resting
/// on the ground, squeezes it, lifts it, holds it and lets it go. The body is the paper's sphere
/// (radius 1 m, 1 kg) or an elongated one that stands for a vessel. Shared by examples/clamp_demo
/// and tests/clamp; not part of the library.

#include <thintool/thintool.h>

#include <functional>
#include <string>
#include <vector>

class btSoftRigidDynamicsWorld;

namespace thintool::scenes {

enum class ClampBody { Sphere, Vessel };
const char* clampBodyName(ClampBody body);

struct ClampSample;

struct ClampRunSettings {
  ClampBody body = ClampBody::Sphere;
  bool friction = true;
  double timeStep = 1.0 / 60;  ///< s
  double squeeze = 0.2;        ///< how much of the body's width the jaws close past first touch
  double liftHeight = 1;       ///< m the handle rises: half the sphere's diameter
  double holdSeconds = 2;      ///< held up
  /// Called after every step (a viewer draws the world there); returning false ends the run.
  std::function<bool(const btSoftRigidDynamicsWorld&, Clamp&, const ClampSample&)> observer;
};

/// One step of the run: the phase (approach, close, lift, hold, release, drop), the clamp's
/// state and forces, and where the body is.
struct ClampSample {
  double time = 0;             ///< s
  std::string phase;
  double opening = 0;          ///< rad
  double grip = 0;             ///< N, ClampForces::grip
  Vec3 onUpperJaw, onLowerJaw; ///< N
  Vec3 onBody;                 ///< N, the jaws' resultant on the body, from their wrenches (ClampForces)
  /// N, the body's momentum change less its weight, Δp/dt - m·g: every force on it but gravity,
  /// measured independently of ThinTool (while it hangs free, the jaws' whole resultant).
  Vec3 bodyNetForce;
  /// N, the resultant of Bullet's pressure forces on the body in the step (kPR·area·normal/volume
  /// at each node): zero on a round body, not on a squeezed mesh, and part of bodyNetForce.
  Vec3 bodyPressure;
  double bodyLowest = 0;       ///< m, the body's lowest node height
  double bodyCentreHeight = 0; ///< m, mean node height
  int crossed = 0;             ///< nodes that passed through either jaw so far
  bool jawInside = false;      ///< a jaw's centre is inside the closed soft surface
};

struct ClampRun {
  std::vector<ClampSample> samples;
  double restCentreHeight = 0;  ///< m, the settled body's mean node height
  double liftedCentreHeight = 0;///< m, at the end of the hold
  double droppedCentreHeight = 0;///< m, after release
  int crossed = 0;              ///< nodes through either jaw over the run
  bool jawEverInside = false;
  /// At rest in the hold: the two jaws' forces along the squeeze axis, averaged over the hold's
  /// last second (N); equal and opposite when the body is held still.
  double upperSqueeze = 0, lowerSqueeze = 0;
  /// Over the same second, vertical (N): the jaws' resultant on the body from their reports, the
  /// body's own pressure resultant, and its momentum balance Δp/dt − m·g, which the two make up.
  double jawsCarry = 0, pressureCarries = 0, momentumBalance = 0;
  double microsecondsPerStep = 0;
};

ClampRun runClamp(const ClampRunSettings& settings);

}  // namespace thintool::scenes
