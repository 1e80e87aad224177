// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "FalconSession.h"

#include <thintool/core/Error.h>

#include <chrono>
#include <iostream>
#include <thread>

namespace thintool::examples {

namespace {
using Clock = std::chrono::steady_clock;
constexpr auto kBetweenLoops = std::chrono::microseconds(200);
}  // namespace

FalconSession::FalconSession(std::unique_ptr<FalconDriver> driver, const std::string& which,
                             const std::string& firmwareFile, const FalconSessionSettings& settings)
    : m_driver(std::move(driver)), m_which(which), m_settings(settings) {
  if (!m_driver->open()) {
    throw Error(m_which + ": cannot open the device (is it plugged in, and may this user open it? udev rules)");
  }
  if (!m_driver->firmwareLoaded()) loadFirmware(firmwareFile);
  home();
}

FalconSession::~FalconSession() {
  m_driver->setForce({0, 0, 0});
  runUntilReply(m_settings.zeroForceLoops);
  m_driver->lightsOff();
  runUntilReply(m_settings.zeroForceLoops);
  m_driver->close();
}

void FalconSession::fail(const std::string& why) {
  m_driver->close();
  throw Error(m_which + ": " + why);
}

void FalconSession::loadFirmware(const std::string& file) {
  if (!m_driver->setFirmwareFile(file)) fail("cannot read the firmware file '" + file + "' (Novint's novint.bin)");
  for (int attempt = 0; attempt < m_settings.firmwareAttempts; ++attempt) {
    if (m_driver->loadFirmware() && m_driver->firmwareLoaded()) return;
    // A failed load leaves the device in a state that only reopening clears.
    m_driver->close();
    if (!m_driver->open()) throw Error(m_which + ": the device went away while its firmware was loading");
  }
  fail("loading the firmware failed " + std::to_string(m_settings.firmwareAttempts) + " times");
}

void FalconSession::home() {
  // No force until every encoder has seen its index: the positions are relative until then.
  m_driver->setForce({0, 0, 0});
  m_driver->setHoming(true);
  std::cerr << m_which << ": homing: pull the grip all the way out, then push it all the way in\n";
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(m_settings.homingTimeout));
  int failed = 0;
  while (!m_driver->homed()) {
    failed = m_driver->runIOLoop() ? 0 : failed + 1;
    if (failed >= m_settings.lostAfterFailedLoops) fail("the device stopped answering while homing (unplugged?)");
    if (Clock::now() > deadline) fail("not homed in time; pull the grip out and push it in to home it");
    std::this_thread::sleep_for(kBetweenLoops);
  }
  m_driver->setHoming(false);
  if (!runUntilReply(m_settings.lostAfterFailedLoops)) fail("the device stopped answering after homing (unplugged?)");
  const std::array<double, 3> p = m_driver->position();
  m_last.position = {p[0], p[1], p[2] - m_settings.workspaceCentreZ};
}

bool FalconSession::runUntilReply(int attempts) {
  for (int k = 0; k < attempts; ++k) {
    if (m_driver->runIOLoop()) return true;
    std::this_thread::sleep_for(kBetweenLoops);
  }
  return false;
}

bool FalconSession::read(double now, haptics::DeviceState& out) {
  m_driver->setForce(m_force);
  if (m_driver->runIOLoop()) {
    m_failedLoops = 0;
    const std::array<double, 3> p = m_driver->position();
    m_last.position = {p[0], p[1], p[2] - m_settings.workspaceCentreZ};
    m_last.buttons = m_driver->buttons();
  } else {
    ++m_failedLoops;
  }
  // A missed reply is not the end of the device: the last state stands until it answers again, or
  // until it has not for long enough to count as unplugged.
  m_last.time = now;
  out = m_last;
  const bool present = m_driver->isOpen() && m_failedLoops < m_settings.lostAfterFailedLoops;
  if (!present) {
    m_force = {0, 0, 0};
    m_driver->setForce(m_force);
  }
  return present;
}

void FalconSession::write(const Vec3& force) { m_force = {force.x, force.y, force.z}; }

}  // namespace thintool::examples
