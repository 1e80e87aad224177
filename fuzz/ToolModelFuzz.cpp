// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// libFuzzer target: the tool-model builder on random meshes and settings. Whatever the input, it
// either throws thintool::Error or returns a model whose every number is finite.

#include "tool/ToolModel.h"

#include <thintool/core/Error.h>

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <limits>

namespace {

using namespace thintool;

Real anyReal(FuzzedDataProvider& data) {
  switch (data.ConsumeIntegralInRange<int>(0, 7)) {
    case 0: return std::numeric_limits<Real>::quiet_NaN();
    case 1: return std::numeric_limits<Real>::infinity();
    case 2: return 0;
    case 3: return data.ConsumeFloatingPointInRange<Real>(-1e-9, 1e-9);
    case 4: return data.ConsumeFloatingPointInRange<Real>(-1e6, 1e6);
    default: return data.ConsumeFloatingPointInRange<Real>(-2, 2);
  }
}

void requireFinite(bool condition) {
  if (!condition) {
    __builtin_trap();
  }
}

void check(const ToolModel& model) {
  for (Index i = 0; i < model.nodeCount(); ++i) {
    requireFinite(isFinite(model.positions[i]) && isFinite(model.normals[i]));
  }
  for (const Plane& plane : model.planes) {
    requireFinite(isFinite(plane.normal) && std::isfinite(plane.offset));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
  FuzzedDataProvider data(bytes, size);
  ConvexMesh mesh;
  if (data.ConsumeBool()) {
    // A box with any extents, its vertices then nudged: near-valid input reaches the builder.
    mesh = makeBoxMesh({anyReal(data), anyReal(data), anyReal(data)});
    const int nudges = data.ConsumeIntegralInRange<int>(0, 3);
    for (int i = 0; i < nudges && !mesh.vertices.empty(); ++i) {
      const auto v = data.ConsumeIntegralInRange<std::size_t>(0, mesh.vertices.size() - 1);
      mesh.vertices[v][data.ConsumeIntegralInRange<int>(0, 2)] += anyReal(data);
    }
  } else {
    // A soup of vertices and triangles.
    const int vertexCount = data.ConsumeIntegralInRange<int>(0, 12);
    for (int i = 0; i < vertexCount; ++i) {
      mesh.vertices.push_back({anyReal(data), anyReal(data), anyReal(data)});
    }
    const int triangleCount = data.ConsumeIntegralInRange<int>(0, 20);
    for (int i = 0; i < triangleCount; ++i) {
      mesh.triangles.push_back({data.ConsumeIntegralInRange<Index>(0, 13), data.ConsumeIntegralInRange<Index>(0, 13),
                                data.ConsumeIntegralInRange<Index>(0, 13)});
    }
  }
  ToolModelSettings settings;
  settings.sampling.layout = static_cast<SamplingLayout>(data.ConsumeIntegralInRange<int>(0, 2));
  settings.sampling.spacing = data.ConsumeBool() ? std::nullopt : std::optional<Real>(anyReal(data));
  settings.sampling.maxNodes = data.ConsumeIntegralInRange<Index>(0, 5000);
  settings.association.enabled = data.ConsumeBool();
  settings.association.maxRayLength = data.ConsumeBool() ? std::nullopt : std::optional<Real>(anyReal(data));
  settings.probeDepth = data.ConsumeBool() ? std::nullopt : std::optional<Real>(anyReal(data));
  try {
    check(buildToolModel(mesh, settings));
  } catch (const Error&) {
    // A clear refusal is the other allowed outcome.
  }
  return 0;
}
