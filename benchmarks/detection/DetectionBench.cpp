// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Building a tool model, and one step of detection: a 0.8 × 0.02 × 0.8 m plate that moved 16.7 mm
// down (1 m/s at 60 Hz) to 5 mm into a sphere of radius 1, tessellated from 1,280 to 81,920
// triangles. As in the Bullet glue, only the faces near the plate's swept box are handed to
// detection. DetectionStep runs the paper's discrete rays and checks (without the reverse ray,
// which the glue casts through Bullet's tree), SweptStep the swept detection, on the same input,
// and SweptStepRoundTool the swept detection of a ball of radius 0.3 m (a hull of 480 edges)
// pressed as far into the same spheres.

#include "TestMeshes.h"

#include "detection/Detection.h"
#include "detection/SweptDetection.h"
#include "response/Response.h"

#include <benchmark/benchmark.h>

#include <utility>

namespace thintool {
namespace {

ToolModel plate(Real spacing) {
  ToolModelSettings settings;
  settings.sampling.spacing = spacing;
  return buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), settings);
}

void BuildToolModel(benchmark::State& state) {
  const Real spacing = 0.4 / Real(state.range(0));
  Index nodes = 0;
  for (auto _ : state) {
    const ToolModel model = plate(spacing);
    nodes = model.nodeCount();
    benchmark::DoNotOptimize(nodes);
  }
  state.counters["nodes"] = nodes;
}
BENCHMARK(BuildToolModel)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMicrosecond);

// The faces whose boxes meet the plate's box grown by the skin, as the glue's gather finds them.
SoftPatch gatherNear(const ConvexMesh& sphere, const Aabb& box) {
  SoftPatch all = test::patchOf(sphere);
  SoftPatch near;
  std::vector<Index> local(all.vertexCount(), kInvalidIndex);
  for (Index f = 0; f < all.faceCount(); ++f) {
    Aabb faceBox;
    for (Index v : all.faces[f]) faceBox.include(all.positions[v]);
    if (!faceBox.overlaps(box)) continue;
    std::array<Index, 3> corners;
    for (int k = 0; k < 3; ++k) {
      const Index v = all.faces[f][k];
      if (local[v] == kInvalidIndex) {
        local[v] = near.vertexCount();
        near.positions.push_back(all.positions[v]);
        near.previousPositions.push_back(all.positions[v]);
        near.inverseMasses.push_back(1);
        near.nodeIds.push_back(v);
      }
      corners[k] = local[v];
    }
    near.faces.push_back(corners);
    near.faceIds.push_back(f);
  }
  return near;
}

constexpr Real kSkin = 0.005;
constexpr Real kDt = 1.0 / 60;
constexpr Real kStepDisplacement = 1.0 / 60;  // 1 m/s at 60 Hz

// A round tool: a ball of radius 0.3 m, the hull of an icosphere of 162 points and 480 edges, as
// Bullet's sphere shapes are round tools (its demos drape cloth over them). Every hull edge is a
// feature edge that swept detection tests against the soft edges near it.
ToolModel roundTool() {
  ToolModelSettings settings;
  settings.sampling.spacing = 0.05;
  return buildToolModel(test::icosphere(0.3, {0, 0, 0}, 2), settings);
}

struct PressedSphere {
  ToolModel model;
  Pose previous;
  Pose pose;
  SoftPatch patch;
  Index sphereFaces = 0;

  // The tool's lowest point ends 5 mm inside the sphere.
  PressedSphere(int subdivisions, ToolModel tool = plate(0.05) /* 576 nodes */) : model(std::move(tool)) {
    const ConvexMesh sphere = test::icosphere(1, {0, 0, 0}, subdivisions);
    sphereFaces = static_cast<Index>(sphere.triangles.size());
    pose.translation = {0, 1 - 0.005 - model.bounds.min.y, 0};
    previous.translation = pose.translation + Vec3{0, kStepDisplacement, 0};
    Aabb box;
    for (const Vec3& v : model.mesh.vertices) {
      box.include(pose.apply(v));
      box.include(previous.apply(v));
    }
    patch = gatherNear(sphere, box.expanded(kSkin));
  }

  void count(benchmark::State& state, const DetectionCounters& counters) const {
    state.counters["softFaces"] = double(sphereFaces);
    state.counters["facesNearTool"] = counters.facesGathered;
    state.counters["toolNodes"] = model.nodeCount();
    state.counters["tests"] = counters.triangleTests;
    state.counters["contacts"] = counters.colliding;
  }
};

void DetectionStep(benchmark::State& state) {
  const PressedSphere scene(int(state.range(0)));
  DetectionInput input;
  input.filters.reverseRay = false;
  PairHistory history;
  DetectionResult result;
  result.contacts.reserve(scene.model.nodeCount());
  const StepContext step{scene.model, scene.pose, scene.pose, kDt, kSkin};
  for (auto _ : state) {
    detectContacts(step, scene.patch, input, history, result);
    benchmark::DoNotOptimize(result.contacts.data());
  }
  scene.count(state, result.counters);
}
BENCHMARK(DetectionStep)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

// Times swept detection on the scene, and writes its counters.
void timeSweptDetection(benchmark::State& state, const PressedSphere& scene) {
  SideMemory memory;
  memory.resize(scene.patch.vertexCount() * 64, scene.patch.faceCount() * 64);
  SweptWorkspace workspace;
  DetectionResult result;
  const StepContext step{scene.model, scene.previous, scene.pose, kDt, kSkin};
  for (auto _ : state) {
    detectSwept(step, scene.patch, memory, workspace, result);
    benchmark::DoNotOptimize(result.contacts.data());
  }
  scene.count(state, result.counters);
}

void SweptStep(benchmark::State& state) { timeSweptDetection(state, PressedSphere(int(state.range(0)))); }
BENCHMARK(SweptStep)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

void SweptStepRoundTool(benchmark::State& state) {
  const PressedSphere scene(int(state.range(0)), roundTool());
  timeSweptDetection(state, scene);
  state.counters["toolEdges"] = double(scene.model.featureEdges.size());
}
BENCHMARK(SweptStepRoundTool)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace thintool
