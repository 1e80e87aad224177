// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ToolShape.h"

#include <thintool/bullet/Convert.h>
#include <thintool/core/Error.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <LinearMath/btConvexHullComputer.h>

#include <sstream>
#include <utility>

namespace thintool::detail {

namespace {

// Directions of a twice-subdivided icosahedron: 162 support points make the hull of a sphere
// deviate from it by under 2 % of its radius.
std::vector<Vec3> sphereDirections() {
  const Real phi = (1 + std::sqrt(Real(5))) / 2;
  std::vector<Vec3> points = {{-1, phi, 0}, {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi}, {0, 1, phi},
                              {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1}, {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  std::vector<std::array<Index, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < 2; ++level) {
    std::vector<std::array<Index, 3>> finer;
    for (const auto& f : faces) {
      Index mid[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3 m = (points[f[k]] + points[f[(k + 1) % 3]]) * Real(0.5);
        // Shared edges produce the same midpoint twice; the hull does not mind duplicates.
        mid[k] = static_cast<Index>(points.size());
        points.push_back(m);
      }
      finer.push_back({f[0], mid[0], mid[2]});
      finer.push_back({f[1], mid[1], mid[0]});
      finer.push_back({f[2], mid[2], mid[1]});
      finer.push_back({mid[0], mid[1], mid[2]});
    }
    faces = finer;
  }
  for (Vec3& p : points) {
    p = normalizedOrZero(p);
  }
  return points;
}

std::vector<btVector3> supportPoints(const btConvexShape& shape, bool withMargin) {
  std::vector<btVector3> points;
  for (const Vec3& d : sphereDirections()) {
    const btVector3 direction = toBt(d);
    points.push_back(withMargin ? shape.localGetSupportingVertex(direction)
                                : shape.localGetSupportingVertexWithoutMargin(direction));
  }
  return points;
}

ConvexMesh convexPieceMesh(const btCollisionShape& shape) {
  if (shape.getShapeType() == BOX_SHAPE_PROXYTYPE) {
    return makeBoxMesh(toVec3(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin()));
  }
  if (shape.getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE) {
    const auto& hull = static_cast<const btConvexHullShape&>(shape);
    std::vector<btVector3> points;
    for (int i = 0; i < hull.getNumPoints(); ++i) {
      points.push_back(hull.getUnscaledPoints()[i] * hull.getLocalScaling());
    }
    return hullOf(points);
  }
  if (shape.isConvex()) {
    const auto& convex = static_cast<const btConvexShape&>(shape);
    return hullOf(supportPoints(convex, !convex.isPolyhedral()));
  }
  std::ostringstream problem;
  problem << "shape '" << shape.getName() << "' is not convex; a tool must be convex or a compound of convex children";
  throw Error(problem.str());
}

}  // namespace

ConvexMesh hullOf(const std::vector<btVector3>& points) {
  ConvexMesh mesh;
  if (points.size() < 4) {
    return mesh;
  }
  std::vector<double> coordinates;
  coordinates.reserve(3 * points.size());
  for (const btVector3& p : points) {
    coordinates.insert(coordinates.end(), {double(p.x()), double(p.y()), double(p.z())});
  }
  btConvexHullComputer hull;
  hull.compute(coordinates.data(), 3 * sizeof(double), static_cast<int>(points.size()), 0, 0);
  // The computer rounds coordinates to a fixed-point grid and merges faces that are coplanar on
  // it. The input points themselves are exact; where they leave a merged face bent beyond the
  // convexity tolerance (many nearly coplanar support points), its own vertices are used.
  for (int i = 0; i < hull.vertices.size(); ++i) {
    const int original = hull.original_vertex_index[i];
    mesh.vertices.push_back(original >= 0 && original < static_cast<int>(points.size()) ? toVec3(points[original])
                                                                                          : toVec3(hull.vertices[i]));
  }
  // Each face is a planar polygon whose edges run counter-clockwise seen from outside.
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const Index anchor = static_cast<Index>(first->getSourceVertex());
    const btConvexHullComputer::Edge* edge = first->getNextEdgeOfFace();
    while (edge->getTargetVertex() != static_cast<int>(anchor)) {
      mesh.triangles.push_back(
          {anchor, static_cast<Index>(edge->getSourceVertex()), static_cast<Index>(edge->getTargetVertex())});
      edge = edge->getNextEdgeOfFace();
    }
  }
  // The computer documents its face loops as counter-clockwise; the signed volume makes sure.
  Real sixVolume = 0;
  for (const auto& t : mesh.triangles) {
    sixVolume += dot(mesh.vertices[t[0]], cross(mesh.vertices[t[1]], mesh.vertices[t[2]]));
  }
  if (sixVolume < 0) {
    for (auto& t : mesh.triangles) {
      std::swap(t[1], t[2]);
    }
  }
  if (!validateConvexMesh(mesh).empty()) {
    for (int i = 0; i < hull.vertices.size(); ++i) {
      mesh.vertices[i] = toVec3(hull.vertices[i]);
    }
  }
  return mesh;
}

std::vector<ShapePiece> shapePieces(const btCollisionShape& shape) {
  std::vector<ShapePiece> pieces;
  if (shape.getShapeType() == COMPOUND_SHAPE_PROXYTYPE) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    if (compound.getNumChildShapes() == 0) {
      throw Error("the compound shape has no children");
    }
    for (int i = 0; i < compound.getNumChildShapes(); ++i) {
      const btCollisionShape& child = *compound.getChildShape(i);
      if (child.getShapeType() == COMPOUND_SHAPE_PROXYTYPE) {
        std::ostringstream problem;
        problem << "child " << i << " is itself a compound; flatten nested compounds into one";
        throw Error(problem.str());
      }
      try {
        pieces.push_back({convexPieceMesh(child), toPose(compound.getChildTransform(i))});
      } catch (const Error& error) {
        std::ostringstream problem;
        problem << "compound child " << i << ": " << error.what();
        throw Error(problem.str());
      }
    }
    return pieces;
  }
  pieces.push_back({convexPieceMesh(shape), Pose{}});
  return pieces;
}

}  // namespace thintool::detail
