// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The segment–triangle kernel: nanoseconds per test on cache-resident random data, segments near
// small triangles so that some hit (the hitRate counter says how many).

#include <thintool/geometry/RayTriangle.h>

#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <vector>

namespace thintool {
namespace {

void SegmentTriangle(benchmark::State& state) {
  constexpr int kCount = 4096;
  std::mt19937 random(1);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  std::vector<std::array<Vec3, 3>> triangles(kCount);
  std::vector<std::array<Vec3, 2>> segments(kCount);
  for (int i = 0; i < kCount; ++i) {
    const Vec3 centre = point();
    triangles[i] = {centre + point() * 0.1, centre + point() * 0.1, centre + point() * 0.1};
    segments[i] = {centre + point() * 0.3, point() * 0.3};
  }
  long hits = 0;
  for (auto _ : state) {
    for (int i = 0; i < kCount; ++i) {
      const auto& t = triangles[i];
      hits += intersectSegmentTriangle(segments[i][0], segments[i][1], t[0], t[1], t[2]).hit;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(state.iterations() * kCount);
  state.counters["hitRate"] = benchmark::Counter(double(hits) / (state.iterations() * kCount));
}
BENCHMARK(SegmentTriangle);

}  // namespace
}  // namespace thintool
