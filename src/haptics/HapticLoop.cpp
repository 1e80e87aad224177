// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/haptics/HapticLoop.h>

#include <algorithm>
#include <cmath>

namespace thintool::haptics {

namespace {

// The statistics cover the latest ticks, kept in rings: order does not matter to them.
constexpr std::size_t kRecordedTicks = std::size_t(1) << 16;  // 65 s at 1 kHz

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) {
    return 0;
  }
  const auto rank = static_cast<std::size_t>(fraction * double(values.size() - 1) + 0.5);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace

HapticLoop::HapticLoop(Device& device, const HapticLoopSettings& settings) : m_device(device), m_settings(settings) {
  m_period.reserve(kRecordedTicks);
  m_latency.reserve(kRecordedTicks);
  m_toolAge.reserve(kRecordedTicks);
}

HapticLoop::~HapticLoop() { stop(); }

double HapticLoop::clockNow() const { return std::chrono::duration<double>(Clock::now() - m_epoch).count(); }

void HapticLoop::start() {
  stop();
  m_stopRequested = false;
  m_running = true;
  m_epoch = Clock::now();
  m_thread = std::thread([this] { run(); });
}

void HapticLoop::stop() {
  m_stopRequested = true;
  if (m_thread.joinable()) {
    m_thread.join();
  }
  m_running = false;
}

void HapticLoop::run() {
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1 / m_settings.rate));
  auto next = m_epoch;
  while (!m_stopRequested && tick(clockNow())) {
    next += period;
    const auto now = Clock::now();
    if (next < now - 10 * period) {
      next = now;  // fell far behind (a debugger, a suspended machine): do not race to catch up
    }
    std::this_thread::sleep_until(next);
  }
  m_running = false;
}

bool HapticLoop::tick(double now) {
  const double started = m_running ? clockNow() : now;
  DeviceState state;
  const bool alive = m_device.read(now, state);
  const Vec3 position = state.position;

  std::unique_lock<std::mutex> lock(m_mutex);
  if (!alive) {
    m_snapshot.finished = true;
    m_deviceForce = Vec3{};
    lock.unlock();
    m_device.write(Vec3{});
    return false;
  }
  const double dt = now - m_snapshot.time;
  const Vec3 velocity = m_snapshot.valid && dt > 0 ? (position - m_snapshot.position) / dt : Vec3{};
  m_snapshot.time = now;
  m_snapshot.position = position;
  m_snapshot.velocity = velocity;
  m_snapshot.worldPosition = m_settings.workspaceOffset + position * m_settings.workspaceScale;
  m_snapshot.buttons = state.buttons;
  m_snapshot.valid = true;
  const bool toolKnown = m_toolTime >= 0;
  const Vec3 toolPosition = toolKnown ? m_toolPosition : position;
  const Vec3 toolVelocity = toolKnown ? m_toolVelocity : velocity;
  const double toolAge = toolKnown ? now - m_toolTime : 0;
  const Vec3 rendered = m_renderedForce;
  lock.unlock();

  CouplingSettings coupling = m_settings.coupling;
  coupling.maxForce = std::min(coupling.maxForce, m_device.limits().maxForce);
  Vec3 unclamped = couplingForceUnclamped(coupling, position, velocity, toolPosition, toolVelocity);
  if (!isFinite(unclamped)) unclamped = Vec3{};
  unclamped += rendered;
  const Real magnitude = length(unclamped);
  const Vec3 force = magnitude > coupling.maxForce ? unclamped * (coupling.maxForce / magnitude) : unclamped;
  m_device.write(force);
  const double written = m_running ? clockNow() : now;

  lock.lock();
  m_deviceForce = force;
  if (length(unclamped) > coupling.maxForce) {
    ++m_clamped;
  }
  const std::size_t slot = m_ticks % kRecordedTicks;
  if (m_latency.size() < kRecordedTicks) {
    m_latency.push_back(written - started);
    m_toolAge.push_back(toolAge);
  } else {
    m_latency[slot] = written - started;
    m_toolAge[slot] = toolAge;
  }
  if (m_ticks > 0) {
    const std::size_t periodSlot = (m_ticks - 1) % kRecordedTicks;
    if (m_period.size() < kRecordedTicks) {
      m_period.push_back(now - m_lastTickStart);
    } else {
      m_period[periodSlot] = now - m_lastTickStart;
    }
  }
  m_lastTickStart = now;
  ++m_ticks;
  return true;
}

void HapticLoop::publishTool(const Vec3& position, const Vec3& velocity) {
  if (!isFinite(position) || !isFinite(velocity)) {
    return;  // the coupling keeps the last sane state rather than sending the hand a NaN
  }
  const double now = m_running ? clockNow() : -1;
  std::lock_guard<std::mutex> lock(m_mutex);
  m_toolPosition = (position - m_settings.workspaceOffset) / m_settings.workspaceScale;
  m_toolVelocity = velocity / m_settings.workspaceScale;
  m_toolTime = now >= 0 ? now : std::max(m_snapshot.time, 0.0);
}

void HapticLoop::publishToolForce(const Vec3& force) {
  if (!isFinite(force)) {
    return;
  }
  std::lock_guard<std::mutex> lock(m_mutex);
  m_renderedForce = force / m_settings.workspaceScale;
}

DeviceSnapshot HapticLoop::device() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_snapshot;
}

Vec3 HapticLoop::toolForce(const Vec3& toolPosition, const Vec3& toolVelocity) const {
  const DeviceSnapshot snapshot = device();
  if (!snapshot.valid) {
    return {};
  }
  const Real scale = m_settings.workspaceScale;
  const Vec3 force = couplingForceUnclamped(m_settings.coupling, snapshot.position, snapshot.velocity,
                                            (toolPosition - m_settings.workspaceOffset) / scale, toolVelocity / scale);
  return isFinite(force) ? force * (-1 / scale) : Vec3{};
}

Vec3 HapticLoop::deviceForce() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_deviceForce;
}

LoopStatistics HapticLoop::statistics() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  LoopStatistics stats;
  stats.ticks = m_ticks;
  stats.clampedTicks = m_clamped;
  if (m_period.empty()) {
    return stats;
  }
  const std::vector<double>& periods = m_period;
  double sum = 0;
  for (double p : periods) {
    sum += p;
  }
  const double mean = sum / double(periods.size());
  double variance = 0;
  for (double p : periods) {
    variance += (p - mean) * (p - mean);
  }
  stats.rate = mean > 0 ? 1 / mean : 0;
  stats.jitter = std::sqrt(variance / double(periods.size()));
  stats.periodMax = *std::max_element(periods.begin(), periods.end());
  stats.periodP50 = percentile(periods, 0.5);
  stats.periodP99 = percentile(periods, 0.99);
  stats.latencyP50 = percentile(m_latency, 0.5);
  stats.latencyP99 = percentile(m_latency, 0.99);
  stats.toolStateAgeP99 = percentile(m_toolAge, 0.99);
  return stats;
}

}  // namespace thintool::haptics
