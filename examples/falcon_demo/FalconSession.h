// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// A Novint Falcon session as a haptics::Device, over the few driver calls it needs, so that the
// session's rules can be tested with a fake driver and built without libnifalcon. The rules follow
// libnifalcon's own command-line tool (f7c727a): the firmware load is retried with the device
// reopened between attempts; the device is homed before any force is sent (its encoders read
// relative until then, and the position jumps when homing completes); the I/O loop, which returns
// false while a reply is pending, is run until a command has gone out.

#include <thintool/haptics/Device.h>

#include <array>
#include <memory>
#include <string>

namespace thintool::examples {

/// The driver calls the session makes (FalconDevice.cpp implements them over libnifalcon).
class FalconDriver {
 public:
  virtual ~FalconDriver() = default;
  virtual bool open() = 0;
  virtual void close() = 0;
  virtual bool isOpen() = 0;
  virtual bool firmwareLoaded() = 0;
  virtual bool setFirmwareFile(const std::string& file) = 0;
  virtual bool loadFirmware() = 0;
  /// Homing mode on, and the LED that tells the user to home (on) or that it is done (off).
  virtual void setHoming(bool homing) = 0;
  virtual bool homed() = 0;
  virtual void setForce(const std::array<double, 3>& force) = 0;
  /// One exchange with the device; false while a reply is pending or on error.
  virtual bool runIOLoop() = 0;
  /// Metres, Stamper frame: x right, y up, z towards the user, origin behind the workspace centre.
  virtual std::array<double, 3> position() = 0;
  virtual unsigned buttons() = 0;
  /// Before closing: every LED off.
  virtual void lightsOff() = 0;
};

struct FalconSessionSettings {
  int firmwareAttempts = 10;          ///< as libnifalcon's command-line tool
  int lostAfterFailedLoops = 1000;    ///< exchanges in a row without a reply: unplugged (1 s at 1 kHz)
  double homingTimeout = 60;          ///< s
  int zeroForceLoops = 1000;          ///< most exchanges tried on exit for the zero force to go out
  double workspaceCentreZ = 0.11;     ///< m, from the Stamper origin to the workspace's centre
};

class FalconSession final : public haptics::Device {
 public:
  /// Opens, loads firmwareFile if the device has no firmware, and homes it (telling the user on
  /// stderr); throws thintool::Error, naming the device as which, on any failure.
  FalconSession(std::unique_ptr<FalconDriver> driver, const std::string& which, const std::string& firmwareFile,
                const FalconSessionSettings& settings = {});
  /// Sends the zero force (exchanges until one completes, at most zeroForceLoops) and closes.
  ~FalconSession() override;
  FalconSession(const FalconSession&) = delete;
  FalconSession& operator=(const FalconSession&) = delete;

  std::string name() const override { return "Novint Falcon"; }
  haptics::DeviceLimits limits() const override { return haptics::DeviceLimits{8, 0}; }
  /// False once the device has not answered for lostAfterFailedLoops exchanges (unplugged): the
  /// force is then zero.
  bool read(double now, haptics::DeviceState& out) override;
  void write(const Vec3& force) override;

 private:
  void loadFirmware(const std::string& file);
  void home();
  bool runUntilReply(int attempts);
  [[noreturn]] void fail(const std::string& why);

  std::unique_ptr<FalconDriver> m_driver;
  std::string m_which;
  FalconSessionSettings m_settings;
  std::array<double, 3> m_force{0, 0, 0};
  haptics::DeviceState m_last;
  int m_failedLoops = 0;
};

}  // namespace thintool::examples
