// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "../../src/bullet/ToolShape.h"

#include <thintool/core/Error.h>

#include <btBulletCollisionCommon.h>

#include <gtest/gtest.h>

namespace thintool::detail {
namespace {

TEST(ToolShape, BoxIsItsHalfExtents) {
  btBoxShape box(btVector3(0.4f, 0.01f, 0.3f));
  const std::vector<ShapePiece> pieces = shapePieces(box);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(validateConvexMesh(pieces[0].mesh), "");
  const Aabb b = bounds(pieces[0].mesh);
  EXPECT_NEAR(b.max.x, 0.4, 1e-6);
  EXPECT_NEAR(b.max.y, 0.01, 1e-6);
  EXPECT_NEAR(b.max.z, 0.3, 1e-6);
}

TEST(ToolShape, HullShapeIsItsPointsWithoutTheMargin) {
  btConvexHullShape hull;
  const btScalar a = 0.05f, h = 0.002f;
  for (btScalar x : {-a, a}) {
    for (btScalar y : {-h, h}) {
      for (btScalar z : {btScalar(-0.1), btScalar(0.1)}) hull.addPoint(btVector3(x, y, z), false);
    }
  }
  hull.addPoint(btVector3(0, 0, 0.12f));  // a pointed tip; also an interior point would be dropped
  hull.addPoint(btVector3(0, 0, 0));
  const std::vector<ShapePiece> pieces = shapePieces(hull);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(validateConvexMesh(pieces[0].mesh), "");
  EXPECT_EQ(pieces[0].mesh.vertices.size(), 9u);
  EXPECT_NEAR(bounds(pieces[0].mesh).max.y, 0.002, 1e-7);
}

TEST(ToolShape, RoundShapesKeepTheirMarginAsSize) {
  btSphereShape sphere(0.5f);
  const ConvexMesh mesh = shapePieces(sphere)[0].mesh;
  EXPECT_EQ(validateConvexMesh(mesh), "");
  for (const Vec3& v : mesh.vertices) EXPECT_NEAR(length(v), 0.5, 1e-6);
  btCylinderShape cylinder(btVector3(0.01f, 0.5f, 0.01f));  // a needle
  EXPECT_EQ(validateConvexMesh(shapePieces(cylinder)[0].mesh), "");
}

TEST(ToolShape, CompoundChildrenBecomePiecesWithTheirTransforms) {
  btBoxShape jaw(btVector3(0.3f, 0.01f, 0.05f));
  btCompoundShape clamp;
  clamp.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 0.1f, 0)), &jaw);
  clamp.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, -0.1f, 0)), &jaw);
  const std::vector<ShapePiece> pieces = shapePieces(clamp);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(pieces[0].transform.translation.y, 0.1, 1e-7);
  EXPECT_NEAR(pieces[1].transform.translation.y, -0.1, 1e-7);

  btCompoundShape nested;
  nested.addChildShape(btTransform::getIdentity(), &clamp);
  EXPECT_THROW(shapePieces(nested), Error);
  btCompoundShape empty;
  EXPECT_THROW(shapePieces(empty), Error);
}

}  // namespace
}  // namespace thintool::detail
