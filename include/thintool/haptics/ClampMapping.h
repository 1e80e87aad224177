// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The paper's mapping of a 3-DoF device onto the clamp (§IV.A): two of the device's axes move
/// the clamp in a plane, the third opens and closes it. The device's own axes are x (right),
/// y (up) and z (towards the user), as a Novint Falcon reports them.

#include <thintool/core/Math.h>
#include <thintool/haptics/Device.h>

namespace thintool::haptics {

struct ClampMapping {
  Vec3 deviceCentre;           ///< m, the device point that maps to the plane's origin, fully open
  Real workspaceScale = 10;    ///< plane metres per device metre
  /// Opening (rad) at deviceCentre.z; pushing the handle away (-z) closes the clamp.
  Real openingAtCentre = kPi / 4;
  Real radiansPerMetre = 30;   ///< opening change per device metre along z
};

struct ClampCommand {
  Real planeX = 0;  ///< m, along the clamp's plane's first axis (device x)
  Real planeY = 0;  ///< m, along its second axis (device y)
  Real opening = 0; ///< rad, not yet clamped to the clamp's range
};

/// The command for a device reading; non-finite input gives a command of NaNs, which
/// thintool::Clamp::setPose ignores for the opening.
inline ClampCommand mapDeviceToClamp(const DeviceState& device, const ClampMapping& mapping) {
  const Vec3 offset = device.position - mapping.deviceCentre;
  return {offset.x * mapping.workspaceScale, offset.y * mapping.workspaceScale,
          mapping.openingAtCentre + offset.z * mapping.radiansPerMetre};
}

}  // namespace thintool::haptics
