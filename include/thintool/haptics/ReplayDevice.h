// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A device that plays a recorded trajectory: a CSV file with a header line and rows
/// "time,x,y,z,buttons" (s, m, m, m, integer), times increasing, |time| <= 1e9 s and
/// |x|, |y|, |z| <= 1e6 m. Between rows the position is
/// interpolated linearly; buttons keep the earlier row's value. The forces written to it are kept,
/// so that a replay can be compared with the recording's run.

#include <thintool/core/Api.h>
#include <thintool/haptics/Device.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace thintool::haptics {

class THINTOOL_API ReplayDevice final : public Device {
 public:
  /// Reads a trajectory; throws thintool::Error naming the file, line and field of the first problem.
  static ReplayDevice fromFile(const std::string& path);
  /// The same from a stream; name stands for the file in messages.
  static ReplayDevice fromStream(std::istream& in, const std::string& name);
  explicit ReplayDevice(std::vector<DeviceState> samples, std::string name = "replay");

  std::string name() const override { return m_name; }
  DeviceLimits limits() const override { return m_limits; }
  void setLimits(const DeviceLimits& limits) { m_limits = limits; }
  /// The recording's state at now (s from its first row); false once now is past its last row.
  bool read(double now, DeviceState& out) override;
  void write(const Vec3& force) override { m_lastForce = force; }

  double duration() const;
  const std::vector<DeviceState>& samples() const { return m_samples; }
  const Vec3& lastForce() const { return m_lastForce; }

 private:
  std::vector<DeviceState> m_samples;
  std::string m_name;
  DeviceLimits m_limits;
  std::size_t m_cursor = 0;
  Vec3 m_lastForce;
};

}  // namespace thintool::haptics
