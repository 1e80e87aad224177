// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "FalconDevice.h"

#include <thintool/core/Error.h>

#include <falcon/core/FalconDevice.h>
#include <falcon/firmware/FalconFirmwareNovintSDK.h>
#include <falcon/grip/FalconGripFourButton.h>
#include <falcon/kinematic/FalconKinematicStamper.h>

namespace thintool::examples {

namespace {
// The Stamper kinematics put the workspace's centre about 11 cm in front of the device.
constexpr double kWorkspaceCentreZ = 0.11;
}  // namespace

struct FalconDevice::Impl {
  libnifalcon::FalconDevice device;
  double force[3] = {0, 0, 0};
  haptics::DeviceState last;
};

FalconDevice::FalconDevice(int index, const std::string& firmwareFile) : m_impl(std::make_unique<Impl>()) {
  libnifalcon::FalconDevice& device = m_impl->device;
  device.setFalconFirmware<libnifalcon::FalconFirmwareNovintSDK>();
  device.setFalconKinematic<libnifalcon::FalconKinematicStamper>();
  device.setFalconGrip<libnifalcon::FalconGripFourButton>();
  if (!device.open(static_cast<uint8_t>(index))) {
    throw Error("Falcon " + std::to_string(index) + ": cannot open the device (is it plugged in, with udev rules?)");
  }
  if (!device.isFirmwareLoaded()) {
    if (!device.setFirmwareFile(firmwareFile)) {
      throw Error("Falcon: cannot read the firmware file '" + firmwareFile + "' (pass Novint's novint.bin)");
    }
    if (!device.loadFirmware(10, false)) {
      throw Error("Falcon: loading the firmware failed");
    }
  }
  device.getFalconFirmware()->setHomingMode(true);
}

FalconDevice::~FalconDevice() {
  double zero[3] = {0, 0, 0};
  m_impl->device.setForce(zero);
  m_impl->device.runIOLoop();
  m_impl->device.close();
}

bool FalconDevice::read(double now, haptics::DeviceState& out) {
  libnifalcon::FalconDevice& device = m_impl->device;
  device.setForce(m_impl->force);
  if (device.runIOLoop()) {
    const double* p = device.getPosition();
    m_impl->last.position = {p[0], p[1], p[2] - kWorkspaceCentreZ};
    m_impl->last.buttons = device.getFalconGrip()->getDigitalInputs();
  }
  // A missed packet is not the end of the device: the last state stands for one tick.
  m_impl->last.time = now;
  out = m_impl->last;
  return device.isOpen();
}

void FalconDevice::write(const Vec3& force) {
  m_impl->force[0] = force.x;
  m_impl->force[1] = force.y;
  m_impl->force[2] = force.z;
}

}  // namespace thintool::examples
