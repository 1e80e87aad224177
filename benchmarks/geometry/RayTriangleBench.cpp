// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The segment–triangle kernels: nanoseconds per test on cache-resident random data, segments near
// small triangles so that some hit (the hitRate counter says how many). SegmentTriangle pairs
// segment i with triangle i; the two SegmentEightTriangles benchmarks test segment i against the
// eight triangles of i's block of the same data, once with the scalar kernel and once with the
// batched one (dispatched, and each variant this CPU runs by name), so that they compare on
// identical pairs.

#include "geometry/RayTriangle.h"

#include <benchmark/benchmark.h>

#include <array>
#include <algorithm>
#include <bitset>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace thintool {
namespace {

constexpr int kCount = 4096;  // a multiple of TriangleBlock::kSize

struct Data {
  std::vector<std::array<Vec3, 3>> triangles;
  std::vector<std::array<Vec3, 2>> segments;  // origin, delta
};

Data randomData() {
  std::mt19937 random(1);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  Data data;
  data.triangles.resize(kCount);
  data.segments.resize(kCount);
  for (int i = 0; i < kCount; ++i) {
    const Vec3 centre = point();
    data.triangles[i] = {centre + point() * 0.1, centre + point() * 0.1, centre + point() * 0.1};
    data.segments[i] = {centre + point() * 0.3, point() * 0.3};
  }
  return data;
}

void SegmentTriangle(benchmark::State& state) {
  const Data data = randomData();
  long hits = 0;
  for (auto _ : state) {
    for (int i = 0; i < kCount; ++i) {
      const auto& t = data.triangles[i];
      hits += intersectSegmentTriangle(data.segments[i][0], data.segments[i][1], t[0], t[1], t[2]).hit;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(state.iterations() * kCount);
  state.counters["hitRate"] = benchmark::Counter(double(hits) / (state.iterations() * kCount));
}
BENCHMARK(SegmentTriangle);

constexpr int kLanes = TriangleBlock::kSize;

void SegmentEightTrianglesScalar(benchmark::State& state) {
  const Data data = randomData();
  long hits = 0;
  for (auto _ : state) {
    for (int i = 0; i < kCount; ++i) {
      const int first = i - i % kLanes;
      for (int k = first; k < first + kLanes; ++k) {
        const auto& t = data.triangles[k];
        hits += intersectSegmentTriangle(data.segments[i][0], data.segments[i][1], t[0], t[1], t[2]).hit;
      }
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(state.iterations() * kCount * kLanes);
  state.counters["hitRate"] = benchmark::Counter(double(hits) / (state.iterations() * kCount * kLanes));
}
BENCHMARK(SegmentEightTrianglesScalar);

// Argument: -1 for the dispatched kernel, else a BlockKernel; a variant the CPU does not run is
// skipped.
void SegmentEightTrianglesBatched(benchmark::State& state) {
  const bool dispatched = state.range(0) < 0;
  const auto kernel = static_cast<BlockKernel>(std::max<std::int64_t>(state.range(0), 0));
  const std::vector<BlockKernel>& available = availableBlockKernels();
  if (!dispatched && std::find(available.begin(), available.end(), kernel) == available.end()) {
    state.SkipWithError("this CPU does not run the kernel");
    return;
  }
  state.SetLabel(dispatched ? std::string("dispatched: ") + blockKernelName(available.back())
                            : blockKernelName(kernel));
  const Data data = randomData();
  std::vector<TriangleBlock> blocks(kCount / kLanes);
  for (int i = 0; i < kCount; ++i) {
    const auto& t = data.triangles[i];
    blocks[i / kLanes].push(t[0], t[1], t[2]);
  }
  long hits = 0;
  for (auto _ : state) {
    for (int i = 0; i < kCount; ++i) {
      const TriangleBlock& block = blocks[i / kLanes];
      const unsigned mask =
          dispatched ? intersectSegmentTriangleBlock(data.segments[i][0], data.segments[i][1], block).mask
                     : intersectSegmentTriangleBlock(kernel, data.segments[i][0], data.segments[i][1], block).mask;
      hits += static_cast<long>(std::bitset<kLanes>(mask).count());
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(state.iterations() * kCount * kLanes);
  state.counters["hitRate"] = benchmark::Counter(double(hits) / (state.iterations() * kCount * kLanes));
}
BENCHMARK(SegmentEightTrianglesBatched)
    ->Arg(-1)
    ->Arg(static_cast<int>(BlockKernel::Portable))
    ->Arg(static_cast<int>(BlockKernel::Avx2))
    ->Arg(static_cast<int>(BlockKernel::Avx512));

}  // namespace
}  // namespace thintool
