// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// A Novint Falcon through libnifalcon, built only where libnifalcon is found. The firmware file
// is Novint's and is not shipped: the user names theirs (novint.bin from Novint's driver package).

#include <thintool/haptics/Device.h>

#include <memory>
#include <string>

namespace thintool::examples {

class FalconDevice final : public haptics::Device {
 public:
  /// Opens Falcon number index, loads the firmware and homes it; throws thintool::Error on failure.
  FalconDevice(int index, const std::string& firmwareFile);
  ~FalconDevice() override;
  std::string name() const override { return "Novint Falcon"; }
  haptics::DeviceLimits limits() const override { return haptics::DeviceLimits{8, 0}; }
  bool read(double now, haptics::DeviceState& out) override;
  void write(const Vec3& force) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace thintool::examples
