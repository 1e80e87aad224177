// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// FalconSession's driver calls over libnifalcon f7c727a (getPosition() and setForce() take
// std::array since its 1.1).

#include "FalconDevice.h"

#include "FalconSession.h"

#include <falcon/core/FalconDevice.h>
#include <falcon/firmware/FalconFirmwareNovintSDK.h>
#include <falcon/grip/FalconGripFourButton.h>
#include <falcon/kinematic/FalconKinematicStamper.h>

namespace thintool::examples {

namespace {

class LibnifalconDriver final : public FalconDriver {
 public:
  explicit LibnifalconDriver(unsigned index) : m_index(index) {
    m_device.setFalconFirmware<libnifalcon::FalconFirmwareNovintSDK>();
    m_device.setFalconKinematic<libnifalcon::FalconKinematicStamper>();
    m_device.setFalconGrip<libnifalcon::FalconGripFourButton>();
  }
  bool open() override { return m_device.open(m_index); }
  void close() override { m_device.close(); }
  bool isOpen() override { return m_device.isOpen(); }
  bool firmwareLoaded() override { return m_device.isFirmwareLoaded(); }
  bool setFirmwareFile(const std::string& file) override { return m_device.setFirmwareFile(file); }
  bool loadFirmware() override { return m_device.loadFirmware(false); }
  void setHoming(bool homing) override {
    m_device.getFalconFirmware()->setHomingMode(homing);
    m_device.getFalconFirmware()->setLEDStatus(homing ? libnifalcon::FalconFirmware::RED_LED
                                                      : libnifalcon::FalconFirmware::GREEN_LED);
  }
  bool homed() override { return m_device.getFalconFirmware()->isHomed(); }
  void setForce(const std::array<double, 3>& force) override { m_device.setForce(force); }
  bool runIOLoop() override { return m_device.runIOLoop(); }
  std::array<double, 3> position() override { return m_device.getPosition(); }
  unsigned buttons() override { return m_device.getFalconGrip()->getDigitalInputs(); }
  void lightsOff() override { m_device.getFalconFirmware()->setLEDStatus(0); }

 private:
  libnifalcon::FalconDevice m_device;
  unsigned m_index;
};

}  // namespace

std::unique_ptr<haptics::Device> openFalcon(int index, const std::string& firmwareFile) {
  return std::make_unique<FalconSession>(std::make_unique<LibnifalconDriver>(static_cast<unsigned>(index)),
                                         "Falcon " + std::to_string(index), firmwareFile);
}

}  // namespace thintool::examples
