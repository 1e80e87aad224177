// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The haptic loop in real time, in its own thread, while this thread publishes tool states at
// 1 kHz as a physics loop would: the rate it achieves, its period's p50 and p99, and the latency
// from a published pose to the force written to the device.

#include <thintool/haptics/HapticLoop.h>

#include <benchmark/benchmark.h>

#include <chrono>
#include <thread>

namespace thintool::haptics {
namespace {

class StillDevice final : public Device {
 public:
  std::string name() const override { return "still"; }
  DeviceLimits limits() const override { return {}; }
  bool read(double now, DeviceState& out) override {
    out.time = now;
    out.position = {0, 0, 0};
    return true;
  }
  void write(const Vec3&) override {}
};

void BM_HapticLoopRealTime(benchmark::State& state) {
  const auto seconds = std::chrono::milliseconds(state.range(0));
  LoopStatistics stats;
  for (auto _ : state) {
    StillDevice device;
    HapticLoop loop(device, HapticLoopSettings{});
    loop.start();
    const auto start = std::chrono::steady_clock::now();
    auto next = start;
    int published = 0;
    while (std::chrono::steady_clock::now() - start < seconds) {
      loop.publishTool({0, 0.001 * (published % 10), 0}, {});
      ++published;
      next += std::chrono::milliseconds(1);
      std::this_thread::sleep_until(next);
    }
    loop.stop();
    stats = loop.statistics();
  }
  state.counters["rate_Hz"] = stats.rate;
  state.counters["period_p50_ms"] = stats.periodP50 * 1e3;
  state.counters["period_p99_ms"] = stats.periodP99 * 1e3;
  state.counters["period_max_ms"] = stats.periodMax * 1e3;
  state.counters["tick_latency_p99_us"] = stats.latencyP99 * 1e6;
  // From a published pose to the force that used it: the pose's age when read, plus the tick.
  state.counters["pose_to_force_p99_us"] = (stats.toolStateAgeP99 + stats.latencyP99) * 1e6;
}
BENCHMARK(BM_HapticLoopRealTime)->Arg(2000)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace thintool::haptics
