// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A haptic device as the haptic loop sees it: a position and buttons in, a force out, in metres,
/// seconds and newtons, in the device's own frame. Part of the optional haptics library; the core
/// library knows nothing of devices.

#include <thintool/core/Api.h>
#include <thintool/core/Math.h>

#include <cstdint>
#include <string>

namespace thintool::haptics {

struct DeviceState {
  double time = 0;          ///< s, on the clock the device was read with
  Vec3 position;            ///< m
  std::uint32_t buttons = 0;  ///< bit i set while button i is down
};

struct DeviceLimits {
  Real maxForce = 8;  ///< N, the largest force the device may be asked for (Novint Falcon: about 8.9 N)
  Real physicalDamping = 0;  ///< N·s/m, the device's own damping, if known (0: assume none)
};

class THINTOOL_API Device {
 public:
  virtual ~Device() = default;
  virtual std::string name() const = 0;
  virtual DeviceLimits limits() const = 0;
  /// Reads the device at time now (s, the haptic loop's clock). False when the device is gone or,
  /// for a recording, over.
  virtual bool read(double now, DeviceState& out) = 0;
  /// Commands a force (N); never more than limits().maxForce in magnitude, the loop clamps it.
  virtual void write(const Vec3& force) = 0;
};

}  // namespace thintool::haptics
