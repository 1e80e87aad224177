// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The Falcon session's rules (examples/falcon_demo/FalconSession.h) against a fake driver: no force
// before homing, firmware retries with the device reopened, the zero force on exit, unplugging.

#include "FalconSession.h"

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace thintool::examples {
namespace {

// What the fake driver saw, kept by the test after the session owns the driver.
struct DriverLog {
  int opens = 0;
  int closes = 0;
  int loadAttempts = 0;
  std::vector<std::array<double, 3>> forcesSent;  // the force at each completed exchange
  std::array<double, 3> lastForceSet{0, 0, 0};     // the force the session last asked for
  bool homingOn = false;
  bool forceWhileHoming = false;  // a non-zero force went out before the device was homed
};

class FakeDriver final : public FalconDriver {
 public:
  explicit FakeDriver(DriverLog& log) : m_log(log) {}
  int loadFailures = 0;         // loads that fail before one succeeds
  int loopsUntilHomed = 5;      // exchanges before the encoders report homed (-1: never)
  int repliesBeforeUnplug = -1;  // exchanges that complete before the device stops answering (-1: never)
  int pendingEveryOther = 0;    // 1: every other exchange has its reply pending

  bool open() override {
    ++m_log.opens;
    m_open = true;
    return true;
  }
  void close() override {
    ++m_log.closes;
    m_open = false;
  }
  bool isOpen() override { return m_open; }
  bool firmwareLoaded() override { return m_firmware; }
  bool setFirmwareFile(const std::string& file) override { return file == "novint.bin"; }
  bool loadFirmware() override {
    ++m_log.loadAttempts;
    m_firmware = m_log.loadAttempts > loadFailures;
    return m_firmware;
  }
  void setHoming(bool homing) override { m_log.homingOn = homing; }
  bool homed() override { return loopsUntilHomed >= 0 && m_exchanges >= loopsUntilHomed; }
  void setForce(const std::array<double, 3>& force) override {
    m_force = force;
    m_log.lastForceSet = force;
  }
  bool runIOLoop() override {
    if (repliesBeforeUnplug >= 0 && m_exchanges >= repliesBeforeUnplug) return false;
    if (pendingEveryOther != 0 && (m_calls++ % 2) == 0) return false;
    ++m_exchanges;
    m_log.forcesSent.push_back(m_force);
    if (!homed() && (m_force[0] != 0 || m_force[1] != 0 || m_force[2] != 0)) m_log.forceWhileHoming = true;
    return true;
  }
  std::array<double, 3> position() override { return {0.01, 0.02, 0.13}; }
  unsigned buttons() override { return 4; }
  void lightsOff() override {}

 private:
  DriverLog& m_log;
  bool m_open = false;
  bool m_firmware = false;
  int m_exchanges = 0;
  int m_calls = 0;
  std::array<double, 3> m_force{0, 0, 0};
};

FalconSessionSettings quickSettings() {
  FalconSessionSettings settings;
  settings.lostAfterFailedLoops = 20;
  settings.homingTimeout = 0.5;
  settings.zeroForceLoops = 20;
  return settings;
}

TEST(FalconSession, HomesWithNoForceThenReadsAbsolutePositions) {
  DriverLog log;
  auto driver = std::make_unique<FakeDriver>(log);
  driver->loopsUntilHomed = 7;
  driver->pendingEveryOther = 1;
  FalconSession session(std::move(driver), "Falcon 0", "novint.bin", quickSettings());
  EXPECT_FALSE(log.homingOn) << "homing mode left on";
  EXPECT_GE(log.forcesSent.size(), 7u);
  session.write({1, 2, 3});
  haptics::DeviceState state;
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(session.read(0.001 * k, state));
  EXPECT_FALSE(log.forceWhileHoming);
  EXPECT_EQ(log.forcesSent.back(), (std::array<double, 3>{1, 2, 3}));
  EXPECT_NEAR(state.position.z, 0.02, 1e-12) << "the workspace centre is 0.11 m along z";
  EXPECT_EQ(state.buttons, 4u);
}

TEST(FalconSession, RetriesTheFirmwareReopeningTheDevice) {
  DriverLog log;
  auto driver = std::make_unique<FakeDriver>(log);
  driver->loadFailures = 3;
  FalconSession session(std::move(driver), "Falcon 0", "novint.bin", quickSettings());
  EXPECT_EQ(log.loadAttempts, 4);
  EXPECT_EQ(log.closes, 3);
  EXPECT_EQ(log.opens, 4);
}

TEST(FalconSession, GivesUpOnTheFirmwareWithAClearError) {
  DriverLog log;
  auto driver = std::make_unique<FakeDriver>(log);
  driver->loadFailures = 100;
  try {
    FalconSession session(std::move(driver), "Falcon 0", "novint.bin", quickSettings());
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("Falcon 0: loading the firmware failed 10 times"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(log.loadAttempts, 10);
  EXPECT_EQ(log.opens, log.closes) << "left open";
}

TEST(FalconSession, AFirmwareFileItCannotReadIsNamed) {
  DriverLog log;
  EXPECT_THROW(FalconSession(std::make_unique<FakeDriver>(log), "Falcon 0", "missing.bin", quickSettings()), Error);
  EXPECT_EQ(log.opens, log.closes);
}

TEST(FalconSession, NotHomedInTimeIsAClearError) {
  DriverLog log;
  auto driver = std::make_unique<FakeDriver>(log);
  driver->loopsUntilHomed = -1;
  EXPECT_THROW(FalconSession(std::move(driver), "Falcon 0", "novint.bin", quickSettings()), Error);
  EXPECT_FALSE(log.forceWhileHoming);
  EXPECT_EQ(log.opens, log.closes);
}

TEST(FalconSession, SendsTheZeroForceOnExitThroughPendingReplies) {
  DriverLog log;
  {
    auto driver = std::make_unique<FakeDriver>(log);
    driver->pendingEveryOther = 1;
    FalconSession session(std::move(driver), "Falcon 0", "novint.bin", quickSettings());
    session.write({4, 0, 0});
    haptics::DeviceState state;
    for (int k = 0; k < 6; ++k) session.read(0.001 * k, state);
    ASSERT_EQ(log.forcesSent.back(), (std::array<double, 3>{4, 0, 0}));
  }
  EXPECT_EQ(log.forcesSent.back(), (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(log.opens, log.closes);
}

TEST(FalconSession, AnUnpluggedDeviceEndsTheSessionWithNoForce) {
  DriverLog log;
  auto driver = std::make_unique<FakeDriver>(log);
  driver->repliesBeforeUnplug = 12;
  FalconSession session(std::move(driver), "Falcon 0", "novint.bin", quickSettings());
  session.write({0, 5, 0});
  haptics::DeviceState state;
  int reads = 0;
  while (session.read(0.001 * reads, state) && reads < 1000) ++reads;
  EXPECT_LT(reads, 1000) << "never noticed";
  EXPECT_GE(reads, quickSettings().lostAfterFailedLoops - 1) << "a few missed replies are not an unplug";
  EXPECT_EQ(log.lastForceSet, (std::array<double, 3>{0, 0, 0})) << "the force stayed on";
  session.write({0, 5, 0});
  EXPECT_FALSE(session.read(1, state));
  EXPECT_EQ(log.lastForceSet, (std::array<double, 3>{0, 0, 0}));
}

}  // namespace
}  // namespace thintool::examples
