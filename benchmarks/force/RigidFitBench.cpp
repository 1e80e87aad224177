// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The indentation measure's rigid fit (force/ContactForce.h): the anchors of a ball of the given
// node count, turned and moved as a whole and dented on one side, fitted once a step from the last
// step's fit, as the glue does.

#include "force/ContactForce.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace thintool {
namespace {

void FitRigidMotion(benchmark::State& state) {
  const auto count = static_cast<Index>(state.range(0));
  std::vector<Vec3> rest(count);
  for (Index i = 0; i < count; ++i) {
    // Points spread over a unit sphere by the golden angle.
    const Real z = 1 - 2 * (Real(i) + Real(0.5)) / Real(count);
    const Real r = std::sqrt(1 - z * z);
    const Real phi = Real(2.399963229728653) * Real(i);
    rest[i] = {r * std::cos(phi), r * std::sin(phi), z};
  }
  RestShape shape;
  shape.capture(rest, std::vector<Real>(count, 1));
  Pose motion;
  motion.rotation = rotationAboutAxis(normalizedOrZero(Vec3{1, 2, 3}), Real(0.3));
  motion.translation = {0.1, -0.2, 0.3};
  std::vector<Vec3> anchors;
  for (const Index node : shape.anchors()) {
    Vec3 p = motion.apply(rest[node]);
    if (rest[node].y > Real(0.8)) p.y -= Real(0.1);  // the dent
    anchors.push_back(p);
  }
  RigidFit fit;
  for (auto _ : state) {
    fit = fitRigidMotion(shape, anchors, fit);
    benchmark::DoNotOptimize(fit);
  }
  state.counters["anchors"] = double(anchors.size());
}
BENCHMARK(FitRigidMotion)->Arg(128)->Arg(1024)->Arg(16384);

}  // namespace
}  // namespace thintool
