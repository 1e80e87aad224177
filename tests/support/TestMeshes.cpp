// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "TestMeshes.h"

#include "geometry/RayTriangle.h"

#include <cmath>
#include <map>
#include <utility>

namespace thintool::test {

ConvexMesh icosphere(Real radius, const Vec3& centre, int subdivisions) {
  const Real phi = (1 + std::sqrt(Real(5))) / 2;
  ConvexMesh mesh;
  mesh.vertices = {{-1, phi, 0}, {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi}, {0, 1, phi},
                   {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1}, {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9},  {5, 11, 4},
                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6},  {3, 6, 8},
                    {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& v : mesh.vertices) {
    v = normalizedOrZero(v);
  }
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<Index, Index>, Index> midpoints;
    auto midpoint = [&](Index a, Index b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) {
        return found->second;
      }
      const Index index = static_cast<Index>(mesh.vertices.size());
      mesh.vertices.push_back(normalizedOrZero(mesh.vertices[a] + mesh.vertices[b]));
      midpoints[key] = index;
      return index;
    };
    std::vector<std::array<Index, 3>> finer;
    for (const auto& t : mesh.triangles) {
      const Index ab = midpoint(t[0], t[1]);
      const Index bc = midpoint(t[1], t[2]);
      const Index ca = midpoint(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    mesh.triangles = finer;
  }
  for (Vec3& v : mesh.vertices) {
    v = centre + v * radius;
  }
  return mesh;
}

SoftPatch patchOf(const ConvexMesh& mesh) {
  SoftPatch patch;
  for (Index v = 0; v < mesh.vertices.size(); ++v) {
    patch.positions.push_back(mesh.vertices[v]);
    patch.previousPositions.push_back(mesh.vertices[v]);
    patch.inverseMasses.push_back(1);
    patch.nodeIds.push_back(v);
  }
  for (Index f = 0; f < mesh.triangles.size(); ++f) {
    patch.faces.push_back(mesh.triangles[f]);
    patch.faceIds.push_back(f);
  }
  patch.orientation = 1;
  return patch;
}

bool BruteForceRayQuery::anyHit(const Vec3& from, const Vec3& delta) const {
  for (const auto& f : m_patch.faces) {
    if (intersectSegmentTriangle(from, delta, m_patch.positions[f[0]], m_patch.positions[f[1]],
                                 m_patch.positions[f[2]])
            .hit) {
      return true;
    }
  }
  return false;
}

}  // namespace thintool::test
