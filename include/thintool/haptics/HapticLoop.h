// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The haptic loop: at 1 kHz, in a thread of its own, it reads the device, computes the virtual
/// coupling's force against the latest tool state the physics published (and adds a force the
/// physics asks to render directly, for a tool that follows the device rigidly), and writes it to
/// the device. The physics thread steps at its own rate, publishes the tool's position and velocity
/// after each step, and applies the coupling's opposite force to the tool before the next.
/// The same tick runs synchronously through tick(), for tests and for replays run as fast as
/// possible, where the loop's clock is the tick count times the period.

#include <thintool/core/Api.h>
#include <thintool/haptics/Device.h>
#include <thintool/haptics/VirtualCoupling.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

namespace thintool::haptics {

struct HapticLoopSettings {
  Real rate = 1000;  ///< Hz
  CouplingSettings coupling;
  /// World position = workspaceOffset + workspaceScale · device position (> 0). The coupling works
  /// in the device's own metres and newtons, so its stiffness is what the hand feels; the tool's
  /// force is the device's divided by workspaceScale, which keeps power equal on both sides.
  Real workspaceScale = 1;
  Vec3 workspaceOffset;
};

/// What the physics reads from the loop: the device's latest state.
struct DeviceSnapshot {
  double time = 0;      ///< s, loop clock
  Vec3 position;        ///< device (m)
  Vec3 velocity;        ///< device (m/s), backward difference over one tick
  Vec3 worldPosition;   ///< the device's point in the world (m)
  std::uint32_t buttons = 0;
  bool valid = false;     ///< at least one tick has read the device
  bool finished = false;  ///< the device stopped answering (a recording ended)
};

/// Over the latest 65,536 ticks (65 s at 1 kHz); ticks and clampedTicks count them all.
struct LoopStatistics {
  std::size_t ticks = 0;
  double rate = 0;           ///< ticks per second of loop clock (Hz)
  double periodP50 = 0;      ///< s
  double periodP99 = 0;      ///< s
  double periodMax = 0;      ///< s
  double jitter = 0;         ///< s, standard deviation of the period
  double latencyP50 = 0;     ///< s, from reading the device to writing its force, within a tick
  double latencyP99 = 0;     ///< s
  double toolStateAgeP99 = 0;  ///< s, how old the tool state a tick used was (physics lag)
  std::size_t clampedTicks = 0;  ///< ticks whose force was clamped to the device's limit
};

class THINTOOL_API HapticLoop {
 public:
  HapticLoop(Device& device, const HapticLoopSettings& settings);
  ~HapticLoop();
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Runs tick() at settings.rate in a new thread, on the steady clock, until stop() or the device ends.
  void start();
  void stop();
  bool running() const { return m_running.load(); }

  /// One tick at loop time now (s): read, couple, write. False once the device has ended.
  bool tick(double now);

  /// Physics side: the tool's state after a step (world, m and m/s).
  void publishTool(const Vec3& position, const Vec3& velocity);
  /// Physics side: a force the world put on a tool that follows the device rigidly (a kinematic
  /// tool, such as the clamp, which no coupling separates from the hand), N, world. The device
  /// feels it directly, divided by workspaceScale as the coupling's is, added to the coupling's
  /// force and clamped with it, until the next call. A force that is not finite is ignored.
  void publishToolForce(const Vec3& force);
  DeviceSnapshot device() const;
  /// The coupling's force on the tool (N, world) for the latest device state and the given tool
  /// state (world): the opposite of what the device feels, before the device's clamp, divided by
  /// workspaceScale.
  Vec3 toolForce(const Vec3& toolPosition, const Vec3& toolVelocity) const;
  /// The force last written to the device (N; the device's axes are the world's).
  Vec3 deviceForce() const;

  LoopStatistics statistics() const;
  const HapticLoopSettings& settings() const { return m_settings; }

 private:
  using Clock = std::chrono::steady_clock;
  void run();
  double clockNow() const;

  Device& m_device;
  HapticLoopSettings m_settings;
  std::thread m_thread;
  std::atomic<bool> m_running{false};
  std::atomic<bool> m_stopRequested{false};
  Clock::time_point m_epoch = Clock::now();

  mutable std::mutex m_mutex;  // guards everything below
  DeviceSnapshot m_snapshot;
  Vec3 m_toolPosition;  // device frame
  Vec3 m_toolVelocity;
  double m_toolTime = -1;
  Vec3 m_deviceForce;
  Vec3 m_renderedForce;  // device frame, from publishToolForce
  // Rings over the latest ticks, preallocated: periods, latencies, ages of the tool state used.
  std::size_t m_ticks = 0;
  double m_lastTickStart = 0;
  std::vector<double> m_period;
  std::vector<double> m_latency;
  std::vector<double> m_toolAge;
  std::size_t m_clamped = 0;
};

}  // namespace thintool::haptics
