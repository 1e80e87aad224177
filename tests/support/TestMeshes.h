// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// Meshes and soft-surface stand-ins for core tests that run without Bullet.

#include "detection/SoftPatch.h"
#include "geometry/ConvexMesh.h"

namespace thintool::test {

/// A closed sphere of the given radius and centre, counter-clockwise seen from outside:
/// 20·4^subdivisions triangles.
ConvexMesh icosphere(Real radius, const Vec3& centre, int subdivisions);

/// The whole mesh as a patch (every face, unit masses), as the glue would gather it.
SoftPatch patchOf(const ConvexMesh& mesh);

/// Check 2's reverse ray against every face of a patch, by brute force.
class BruteForceRayQuery final : public SoftSurfaceRayQuery {
 public:
  explicit BruteForceRayQuery(const SoftPatch& patch) : m_patch(patch) {}
  bool anyHit(const Vec3& from, const Vec3& delta) const override;

 private:
  const SoftPatch& m_patch;
};

}  // namespace thintool::test
