// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/ConvexMesh.h"
#include "geometry/RayTriangle.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

namespace thintool {

namespace {

// Relative tolerances, as fractions of the mesh's bounding-box diagonal.
constexpr Real kConvexityTolerance = 1e-6;
constexpr Real kZeroAreaTolerance = 1e-12;

}  // namespace

Aabb bounds(const ConvexMesh& mesh) {
  Aabb box;
  for (const Vec3& v : mesh.vertices) {
    box.include(v);
  }
  return box;
}

std::string validateConvexMesh(const ConvexMesh& mesh) {
  std::ostringstream problem;
  if (mesh.vertices.size() < 4 || mesh.triangles.size() < 4) {
    problem << "the mesh is empty or flat: " << mesh.vertices.size() << " vertices and " << mesh.triangles.size()
            << " triangles, a closed convex piece needs at least 4 of each";
    return problem.str();
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!isFinite(mesh.vertices[i])) {
      problem << "vertex " << i << " has a coordinate that is not finite";
      return problem.str();
    }
  }
  const Index vertexCount = static_cast<Index>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (Index corner : mesh.triangles[t]) {
      if (corner >= vertexCount) {
        problem << "triangle " << t << " names vertex " << corner << " of " << vertexCount;
        return problem.str();
      }
    }
  }

  const Real size = length(bounds(mesh).extent());
  if (!(size > 0)) {
    problem << "all vertices coincide";
    return problem.str();
  }
  // A flat shape (a spatula modelled as a quad, a box of zero height) has no inside to keep the
  // soft body out of, and no sides to tell apart: say so, rather than name one of its slivers.
  Index widest = 0;
  Real widestArea = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Real area = length(triangleNormal(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]));
    if (area > widestArea) {
      widestArea = area;
      widest = static_cast<Index>(t);
    }
  }
  if (widestArea > 0) {
    const auto& tri = mesh.triangles[widest];
    const Vec3 normal = normalizedOrZero(
        triangleNormal(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]));
    Real thickness = 0;
    for (const Vec3& v : mesh.vertices) {
      thickness = std::max(thickness, std::abs(dot(normal, v - mesh.vertices[tri[0]])));
    }
    if (thickness <= kZeroAreaTolerance * size) {
      problem << "the shape is flat (zero thickness); a thin tool needs a thickness, even of a micrometre";
      return problem.str();
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 n = triangleNormal(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    if (length(n) <= kZeroAreaTolerance * size * size) {
      problem << "triangle " << t << " has zero area";
      return problem.str();
    }
  }

  // Closed and consistently wound: every directed edge appears once and its reverse once.
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(tri[k], tri[(k + 1) % 3]);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 1; k < edges.size(); ++k) {
    if (edges[k] == edges[k - 1]) {
      problem << "edge " << edges[k].first << "-" << edges[k].second
              << " is used twice in the same direction: duplicated faces or inconsistent winding";
      return problem.str();
    }
  }
  for (const auto& edge : edges) {
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(edge.second, edge.first))) {
      problem << "edge " << edge.first << "-" << edge.second << " has no neighbouring triangle: the mesh is not closed";
      return problem.str();
    }
  }

  const std::vector<Plane> planes = facePlanes(mesh);
  Real insideVotes = 0;
  for (std::size_t t = 0; t < planes.size(); ++t) {
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      const Real d = planes[t].signedDistance(mesh.vertices[i]);
      insideVotes += d < 0 ? 1 : 0;
      if (d > kConvexityTolerance * size) {
        // An inward-wound closed mesh has every vertex in front of every face.
        const bool allInFront = std::all_of(mesh.vertices.begin(), mesh.vertices.end(), [&](const Vec3& v) {
          return planes[t].signedDistance(v) >= -kConvexityTolerance * size;
        });
        if (allInFront) {
          problem << "triangle " << t << " faces inwards: the winding must be counter-clockwise seen from outside";
        } else {
          problem << "the mesh is not convex: vertex " << i << " lies " << d << " in front of triangle " << t;
        }
        return problem.str();
      }
    }
  }
  if (insideVotes == 0) {
    problem << "the mesh encloses no volume";
    return problem.str();
  }
  return {};
}

std::vector<Plane> facePlanes(const ConvexMesh& mesh) {
  std::vector<Plane> planes;
  planes.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3 n = normalizedOrZero(triangleNormal(a, mesh.vertices[tri[1]], mesh.vertices[tri[2]]));
    planes.push_back({n, dot(n, a)});
  }
  return planes;
}

Real thicknessAcrossFaces(const ConvexMesh& mesh, const std::vector<Plane>& planes) {
  Real thinnest = std::numeric_limits<Real>::max();
  for (const Plane& plane : planes) {
    Real lowest = std::numeric_limits<Real>::max();
    for (const Vec3& v : mesh.vertices) {
      lowest = std::min(lowest, dot(plane.normal, v));
    }
    thinnest = std::min(thinnest, plane.offset - lowest);
  }
  return thinnest;
}

Real exitDistance(const std::vector<Plane>& planes, const Vec3& point, const Vec3& direction) {
  // A convex piece is the intersection of its half-spaces; the ray leaves through the nearest
  // plane it is heading out of.
  Real nearest = std::numeric_limits<Real>::max();
  for (const Plane& plane : planes) {
    const Real approach = dot(plane.normal, direction);
    if (approach <= 0) {
      continue;
    }
    const Real distance = -plane.signedDistance(point) / approach;
    nearest = std::min(nearest, std::max<Real>(distance, 0));
  }
  return nearest;
}

ConvexMesh makeBoxMesh(const Vec3& h) {
  ConvexMesh box;
  for (int i = 0; i < 8; ++i) {
    box.vertices.push_back({(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  }
  // Two counter-clockwise triangles per face, seen from outside.
  box.triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},   // -x, +x
                   {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // -y, +y
                   {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};  // -z, +z
  return box;
}

}  // namespace thintool
