// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/haptics/VirtualCoupling.h>

namespace thintool::haptics {

CouplingCheck checkStability(const CouplingSettings& coupling, Real samplePeriod, Real deviceDamping) {
  CouplingCheck check;
  check.minimumDamping = coupling.stiffness * samplePeriod / 2;
  check.stable = coupling.damping > check.minimumDamping;
  check.passive = deviceDamping > check.minimumDamping + coupling.damping;
  return check;
}

Vec3 couplingForceUnclamped(const CouplingSettings& coupling, const Vec3& devicePosition,
                            const Vec3& deviceVelocity, const Vec3& toolPosition, const Vec3& toolVelocity) {
  return (toolPosition - devicePosition) * coupling.stiffness + (toolVelocity - deviceVelocity) * coupling.damping;
}

Vec3 couplingForce(const CouplingSettings& coupling, const Vec3& devicePosition, const Vec3& deviceVelocity,
                   const Vec3& toolPosition, const Vec3& toolVelocity) {
  const Vec3 force = couplingForceUnclamped(coupling, devicePosition, deviceVelocity, toolPosition, toolVelocity);
  if (!isFinite(force)) {
    return {};
  }
  const Real magnitude = length(force);
  return magnitude > coupling.maxForce ? force * (coupling.maxForce / magnitude) : force;
}

}  // namespace thintool::haptics
