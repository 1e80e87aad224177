// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "TetraBlock.h"

#include <thintool/core/Error.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace thintool::scenes {

namespace {

// Runs f with the process's standard output sent to /dev/null: Bullet's CreateFromTetGenData
// prints its node, link, face and tetrahedron counts there, into the tools' own output.
template <typename F>
auto withQuietStdout(F f) {
  std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO);
  const int null = open("/dev/null", O_WRONLY);
  if (saved >= 0 && null >= 0) dup2(null, STDOUT_FILENO);
  auto result = f();
  std::fflush(stdout);
  if (saved >= 0) {
    dup2(saved, STDOUT_FILENO);
    close(saved);
  }
  if (null >= 0) close(null);
  return result;
}

}  // namespace

btSoftBody* createTetraBlock(btSoftBodyWorldInfo& info, const Vec3& centre, const Vec3& size,
                             const std::array<int, 3>& cells) {
  if (cells[0] < 1 || cells[1] < 1 || cells[2] < 1) throw Error("scene: a tetra block needs at least one cell a side");
  const int sideX = cells[0] + 1;
  const int sideY = cells[1] + 1;
  const int sideZ = cells[2] + 1;
  auto nodeIndex = [sideX, sideY](int i, int j, int k) { return (k * sideY + j) * sideX + i; };
  std::vector<Vec3> positions;
  std::string nodeText = std::to_string(sideX * sideY * sideZ) + " 3 0 0\n";
  for (int k = 0; k < sideZ; ++k) {
    for (int j = 0; j < sideY; ++j) {
      for (int i = 0; i < sideX; ++i) {
        const Vec3 p = centre + Vec3{(i - cells[0] / 2.0) * (size.x / cells[0]), (j - cells[1] / 2.0) * (size.y / cells[1]),
                                     (k - cells[2] / 2.0) * (size.z / cells[2])};
        positions.push_back(p);
        char line[160];
        std::snprintf(line, sizeof line, "%d %.9g %.9g %.9g\n", nodeIndex(i, j, k), p.x, p.y, p.z);
        nodeText += line;
      }
    }
  }
  std::vector<std::array<int, 4>> tetras;
  static constexpr int kAxisOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < cells[2]; ++k) {
    for (int j = 0; j < cells[1]; ++j) {
      for (int i = 0; i < cells[0]; ++i) {
        for (const auto& order : kAxisOrders) {
          int corner[3] = {i, j, k};
          std::array<int, 4> tetra{};
          tetra[0] = nodeIndex(corner[0], corner[1], corner[2]);
          for (int step = 0; step < 3; ++step) {
            ++corner[order[step]];
            tetra[std::size_t(step) + 1] = nodeIndex(corner[0], corner[1], corner[2]);
          }
          tetras.push_back(tetra);
        }
      }
    }
  }
  std::string eleText = std::to_string(tetras.size()) + " 4 0\n";
  for (std::size_t t = 0; t < tetras.size(); ++t) {
    eleText += std::to_string(t) + " " + std::to_string(tetras[t][0]) + " " + std::to_string(tetras[t][1]) + " " +
               std::to_string(tetras[t][2]) + " " + std::to_string(tetras[t][3]) + "\n";
  }
  btSoftBody* body = withQuietStdout([&] {
    return btSoftBodyHelpers::CreateFromTetGenData(info, eleText.c_str(), nullptr, nodeText.c_str(), true, true, false);
  });

  // Each tetrahedron's face with the corner opposite it; a face met once is on the surface.
  struct FaceUse {
    std::array<int, 3> corners;
    int opposite;
    int uses;
  };
  std::map<std::array<int, 3>, FaceUse> faces;
  for (const std::array<int, 4>& t : tetras) {
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> corners{};
      int n = 0;
      for (int c = 0; c < 4; ++c) {
        if (c != skip) corners[std::size_t(n++)] = t[std::size_t(c)];
      }
      std::array<int, 3> key = corners;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, FaceUse{corners, t[std::size_t(skip)], 0});
      ++it->second.uses;
    }
  }
  for (const auto& [key, face] : faces) {
    if (face.uses != 1) continue;
    std::array<int, 3> c = face.corners;
    const Vec3& a = positions[std::size_t(c[0])];
    const Vec3 normal = cross(positions[std::size_t(c[1])] - a, positions[std::size_t(c[2])] - a);
    if (dot(normal, positions[std::size_t(face.opposite)] - a) > 0) std::swap(c[1], c[2]);
    body->appendFace(c[0], c[1], c[2]);
    for (int e = 0; e < 3; ++e) body->appendLink(c[std::size_t(e)], c[std::size_t((e + 1) % 3)], nullptr, true);
  }
  return body;
}

}  // namespace thintool::scenes
