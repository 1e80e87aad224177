// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// libFuzzer target: the trajectory (CSV) loader. Any text either loads, giving finite positions at
// any time, or throws thintool::Error.

#include <thintool/core/Error.h>
#include <thintool/haptics/ReplayDevice.h>

#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(bytes), size));
  try {
    thintool::haptics::ReplayDevice device = thintool::haptics::ReplayDevice::fromStream(in, "fuzz.csv");
    thintool::haptics::DeviceState state;
    for (double t : {-1.0, 0.0, device.duration() * 0.37, device.duration(), device.duration() + 1}) {
      if (device.read(t, state) && !thintool::isFinite(state.position)) {
        __builtin_trap();
      }
    }
  } catch (const thintool::Error&) {
  }
  return 0;
}
