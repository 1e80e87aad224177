// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The spring–damper between the device's point and the simulated tool (Colgate, Stanley &
/// Brown, "Issues in the haptic display of tool use", 1995). The device feels the coupling, not
/// the tissue directly: the physics may run slower than the device and the tool may stop at a
/// surface the hand goes on pushing into, and the coupling keeps the rendered stiffness within
/// what the device can show without going unstable.
///
/// Stability. The device reads its position and holds the force for one sample period T; that
/// hold acts on the hand like a damper of −K·T/2 (Gillespie & Cutkosky, 1996). The coupling's
/// damping B, on the velocity estimated by backward difference, must exceed it: B > K·T/2, which
/// checkStability() reports. Colgate & Schenkel's condition for passivity against any user,
/// b > K·T/2 + |B| with b the device's own damping, is stricter and needs a b that a Falcon does not
/// have; it is reported too, as a fact about the device, not enforced.

#include <thintool/core/Api.h>
#include <thintool/core/Math.h>

namespace thintool::haptics {

struct CouplingSettings {
  Real stiffness = 3000;  ///< K (N/m): 3 N/mm, about the stiffest a Novint Falcon renders
  Real damping = 3;       ///< B (N·s/m): K·T at 1 kHz, twice the bound
  Real maxForce = 8;      ///< N, the device force is clamped to it
};

struct CouplingCheck {
  bool stable = false;   ///< B > K·T/2
  bool passive = false;  ///< device damping > K·T/2 + B
  Real minimumDamping = 0;  ///< K·T/2 (N·s/m)
};

THINTOOL_API CouplingCheck checkStability(const CouplingSettings& coupling, Real samplePeriod, Real deviceDamping);

/// Force on the device (N), clamped to maxForce: K·(tool − device) + B·(toolVelocity − deviceVelocity).
/// The tool feels the opposite, unclamped.
THINTOOL_API Vec3 couplingForce(const CouplingSettings& coupling, const Vec3& devicePosition,
                                const Vec3& deviceVelocity, const Vec3& toolPosition, const Vec3& toolVelocity);

/// The same force before the clamp.
THINTOOL_API Vec3 couplingForceUnclamped(const CouplingSettings& coupling, const Vec3& devicePosition,
                                         const Vec3& deviceVelocity, const Vec3& toolPosition,
                                         const Vec3& toolVelocity);

}  // namespace thintool::haptics
