// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The session follows libnifalcon's own command-line tool (f7c727a): the firmware is loaded with
// the device reopened between failed attempts, the device is homed before any force is sent (its
// encoders read relative until then, and the position jumps when homing completes), and
// runIOLoop(), which returns false while a reply is pending, is run until a command has gone out.

#include "FalconDevice.h"

#include <thintool/core/Error.h>

#include <falcon/core/FalconDevice.h>
#include <falcon/firmware/FalconFirmwareNovintSDK.h>
#include <falcon/grip/FalconGripFourButton.h>
#include <falcon/kinematic/FalconKinematicStamper.h>

#include <array>
#include <chrono>
#include <iostream>
#include <thread>

namespace thintool::examples {

namespace {

// The Stamper kinematics put the workspace's centre about 11 cm in front of the device.
constexpr double kWorkspaceCentreZ = 0.11;
// libnifalcon's command-line tool tries the firmware load this many times.
constexpr int kFirmwareAttempts = 10;
// I/O loops in a row without a reply after which the device counts as gone: about a second at the
// haptic loop's 1 kHz (a reply is normally pending for one or two loops).
constexpr int kLostAfterFailedLoops = 1000;
// Longest wait for the user to home the device.
constexpr auto kHomingTimeout = std::chrono::seconds(60);
// Bounds the loops run on exit for the zero force to go out.
constexpr int kZeroForceLoops = 1000;

using Clock = std::chrono::steady_clock;

// Runs I/O loops until one completes, at most attempts of them, a little apart.
bool runUntilReply(libnifalcon::FalconDevice& device, int attempts) {
  for (int k = 0; k < attempts; ++k) {
    if (device.runIOLoop()) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

}  // namespace

struct FalconDevice::Impl {
  libnifalcon::FalconDevice device;
  std::array<double, 3> force{0, 0, 0};
  haptics::DeviceState last;
  int failedLoops = 0;
};

FalconDevice::FalconDevice(int index, const std::string& firmwareFile) : m_impl(std::make_unique<Impl>()) {
  libnifalcon::FalconDevice& device = m_impl->device;
  device.setFalconFirmware<libnifalcon::FalconFirmwareNovintSDK>();
  device.setFalconKinematic<libnifalcon::FalconKinematicStamper>();
  device.setFalconGrip<libnifalcon::FalconGripFourButton>();
  const std::string which = "Falcon " + std::to_string(index);
  if (!device.open(static_cast<unsigned>(index))) {
    throw Error(which + ": cannot open the device (is it plugged in, and may this user open it? udev rules)");
  }
  if (!device.isFirmwareLoaded()) {
    if (!device.setFirmwareFile(firmwareFile)) {
      device.close();
      throw Error(which + ": cannot read the firmware file '" + firmwareFile + "' (Novint's novint.bin)");
    }
    bool loaded = false;
    for (int attempt = 0; attempt < kFirmwareAttempts && !loaded; ++attempt) {
      loaded = device.loadFirmware(false) && device.isFirmwareLoaded();
      if (!loaded) {
        // A failed load leaves the device in a state that only reopening clears.
        device.close();
        if (!device.open(static_cast<unsigned>(index))) {
          throw Error(which + ": the device went away while its firmware was loading");
        }
      }
    }
    if (!loaded) {
      device.close();
      throw Error(which + ": loading the firmware failed " + std::to_string(kFirmwareAttempts) + " times");
    }
  }

  // Homing, with no force: until every encoder has seen its index the positions are relative.
  auto firmware = device.getFalconFirmware();
  firmware->setHomingMode(true);
  firmware->setLEDStatus(libnifalcon::FalconFirmware::RED_LED);
  device.setForce({0, 0, 0});
  std::cerr << which << ": homing: pull the grip all the way out, then push it all the way in\n";
  const Clock::time_point deadline = Clock::now() + kHomingTimeout;
  int failed = 0;
  while (!firmware->isHomed()) {
    failed = device.runIOLoop() ? 0 : failed + 1;
    if (failed >= kLostAfterFailedLoops) {
      device.close();
      throw Error(which + ": the device stopped answering while homing (unplugged?)");
    }
    if (Clock::now() > deadline) {
      device.close();
      throw Error(which + ": not homed within 60 s; pull the grip out and push it in to home it");
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  firmware->setLEDStatus(libnifalcon::FalconFirmware::GREEN_LED);
  if (!runUntilReply(device, kLostAfterFailedLoops)) {
    device.close();
    throw Error(which + ": the device stopped answering after homing (unplugged?)");
  }
  const std::array<double, 3> p = device.getPosition();
  m_impl->last.position = {p[0], p[1], p[2] - kWorkspaceCentreZ};
}

FalconDevice::~FalconDevice() {
  // The zero force is sent however the session ends: a loop that completes has written it.
  libnifalcon::FalconDevice& device = m_impl->device;
  device.setForce({0, 0, 0});
  runUntilReply(device, kZeroForceLoops);
  device.getFalconFirmware()->setLEDStatus(0);
  runUntilReply(device, kZeroForceLoops);
  device.close();
}

bool FalconDevice::read(double now, haptics::DeviceState& out) {
  libnifalcon::FalconDevice& device = m_impl->device;
  device.setForce(m_impl->force);
  if (device.runIOLoop()) {
    m_impl->failedLoops = 0;
    const std::array<double, 3> p = device.getPosition();
    m_impl->last.position = {p[0], p[1], p[2] - kWorkspaceCentreZ};
    m_impl->last.buttons = device.getFalconGrip()->getDigitalInputs();
  } else {
    ++m_impl->failedLoops;
  }
  // A missed reply is not the end of the device: the last state stands until it answers again, or
  // until it has not for long enough to count as unplugged.
  m_impl->last.time = now;
  out = m_impl->last;
  const bool present = device.isOpen() && m_impl->failedLoops < kLostAfterFailedLoops;
  if (!present) {
    m_impl->force = {0, 0, 0};
  }
  return present;
}

void FalconDevice::write(const Vec3& force) { m_impl->force = {force.x, force.y, force.z}; }

}  // namespace thintool::examples
