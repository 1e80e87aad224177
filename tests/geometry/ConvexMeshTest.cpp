// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "TestMeshes.h"

#include "geometry/ConvexMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

namespace thintool {
namespace {

TEST(ConvexMesh, BoxAndIcosphereAreValid) {
  EXPECT_EQ(validateConvexMesh(makeBoxMesh({0.4, 0.01, 0.4})), "");
  EXPECT_EQ(validateConvexMesh(test::icosphere(1, {0, 1, 0}, 2)), "");
}

TEST(ConvexMesh, ThicknessAndExitDistanceOfAPlate) {
  const ConvexMesh plate = makeBoxMesh({0.4, 0.01, 0.3});
  const std::vector<Plane> planes = facePlanes(plate);
  EXPECT_NEAR(thicknessAcrossFaces(plate, planes), 0.02, 1e-12);
  EXPECT_NEAR(exitDistance(planes, {0.1, -0.01, 0.1}, {0, 1, 0}), 0.02, 1e-12);
  EXPECT_NEAR(exitDistance(planes, {0.4, 0, 0}, {-1, 0, 0}), 0.8, 1e-12);
}

TEST(ConvexMesh, RejectsBrokenMeshesWithTheirProblem) {
  EXPECT_NE(validateConvexMesh(ConvexMesh{}).find("empty"), std::string::npos);

  ConvexMesh nan = makeBoxMesh({1, 1, 1});
  nan.vertices[3].x = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_NE(validateConvexMesh(nan).find("not finite"), std::string::npos);

  ConvexMesh outOfRange = makeBoxMesh({1, 1, 1});
  outOfRange.triangles[0][1] = 99;
  EXPECT_NE(validateConvexMesh(outOfRange).find("names vertex"), std::string::npos);

  ConvexMesh open = makeBoxMesh({1, 1, 1});
  open.triangles.pop_back();
  EXPECT_NE(validateConvexMesh(open).find("not closed"), std::string::npos);

  ConvexMesh flipped = makeBoxMesh({1, 1, 1});
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_NE(validateConvexMesh(flipped).find("inwards"), std::string::npos);

  ConvexMesh oneFlipped = makeBoxMesh({1, 1, 1});
  std::swap(oneFlipped.triangles[0][1], oneFlipped.triangles[0][2]);
  EXPECT_NE(validateConvexMesh(oneFlipped).find("inconsistent winding"), std::string::npos);

  EXPECT_NE(validateConvexMesh(makeBoxMesh({1, 0, 1})).find("flat"), std::string::npos);
  EXPECT_EQ(validateConvexMesh(makeBoxMesh({1, 1e-6, 1})), "") << "a micrometre is a thickness";

  ConvexMesh dented = makeBoxMesh({1, 1, 1});
  dented.vertices[7] = {0.2, 0.2, 0.2};  // a corner pushed inside
  EXPECT_NE(validateConvexMesh(dented).find("not convex"), std::string::npos);

  ConvexMesh flat = makeBoxMesh({1, 0, 1});
  EXPECT_NE(validateConvexMesh(flat), "");
}

}  // namespace
}  // namespace thintool
