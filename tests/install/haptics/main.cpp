// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Runs the installed package's haptic loop, tick by tick, against a device held still 1 cm below
// the tool: the coupling must pull the device up with the device's largest force, 8 N.

#include <thintool/haptics/HapticLoop.h>

#include <cmath>
#include <cstdio>

namespace {

class StillDevice final : public thintool::haptics::Device {
 public:
  std::string name() const override { return "still"; }
  thintool::haptics::DeviceLimits limits() const override { return {}; }
  bool read(double now, thintool::haptics::DeviceState& out) override {
    out.time = now;
    out.position = {0, 0, 0};
    return true;
  }
  void write(const thintool::Vec3& force) override { written = force; }
  thintool::Vec3 written;
};

}  // namespace

int main() {
  StillDevice device;
  thintool::haptics::HapticLoop loop(device, thintool::haptics::HapticLoopSettings{});
  loop.publishTool({0, 0.01, 0}, {0, 0, 0});
  for (int k = 0; k < 10; ++k) {
    if (!loop.tick(k * 0.001)) return 1;
  }
  const double up = device.written.y;
  std::printf("haptic loop from the installed package: device force %.3f N up\n", up);
  return std::abs(up - 8) < 1e-9 && device.written.x == 0 && device.written.z == 0 ? 0 : 1;
}
