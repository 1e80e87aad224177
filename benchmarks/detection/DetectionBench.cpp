// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Building a tool model, and one step of detection: a 0.8 × 0.02 × 0.8 m plate pressed 5 mm into
// a sphere of radius 1 tessellated from 1,280 to 81,920 triangles. As in the Bullet glue, only the
// faces near the plate are handed to detection; the reverse ray runs against the whole surface.

#include "TestMeshes.h"

#include <thintool/detection/Detection.h>
#include <thintool/response/Response.h>

#include <benchmark/benchmark.h>

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

void DetectionStep(benchmark::State& state) {
  const ConvexMesh sphere = test::icosphere(1, {0, 0, 0}, int(state.range(0)));
  const SoftPatch whole = test::patchOf(sphere);
  const test::BruteForceRayQuery reverse(whole);
  const ToolModel model = plate(0.05);  // 576 nodes
  constexpr Real kSkin = 0.005;
  Pose pose;
  pose.translation = {0, 1 - 0.005 + 0.01, 0};
  Aabb box;
  for (const Vec3& v : model.mesh.vertices) box.include(pose.apply(v));
  const SoftPatch patch = gatherNear(sphere, box.expanded(kSkin));
  DetectionParameters parameters;
  parameters.skin = kSkin;
  parameters.filters.reverseRay = false;  // the brute-force query would dominate; the glue uses a tree
  PairHistory history;
  DetectionWorkspace workspace;
  std::vector<Contact> contacts;
  contacts.reserve(model.nodeCount());
  DetectionCounters counters;
  for (auto _ : state) {
    detectContacts(model, pose, patch, &reverse, parameters, history, workspace, contacts, counters);
    benchmark::DoNotOptimize(contacts.data());
  }
  state.counters["softFaces"] = double(sphere.triangles.size());
  state.counters["facesNearTool"] = counters.facesGathered;
  state.counters["toolNodes"] = model.nodeCount();
  state.counters["triangleTests"] = counters.triangleTests;
  state.counters["contacts"] = counters.colliding;
}
BENCHMARK(DetectionStep)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace thintool
