// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/SolidAngle.h"

#include <gtest/gtest.h>

#include <array>

namespace thintool {
namespace {

// A unit cube's twelve triangles, counter-clockwise seen from outside: the winding number is 1 at
// any point inside, 0 at any point outside, and turns sign with the faces.
Real cubeWindingNumber(const Vec3& p, bool flipped) {
  const Vec3 corner[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::array<std::array<int, 3>, 12> faces{{{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                                  {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}}};
  Real total = 0;
  for (const auto& f : faces) {
    const Vec3 a = corner[f[0]] - p;
    const Vec3 b = corner[f[flipped ? 2 : 1]] - p;
    const Vec3 c = corner[f[flipped ? 1 : 2]] - p;
    total += triangleSolidAngle(a, b, c);
  }
  return total / (4 * kPi);
}

TEST(SolidAngle, ATriangleFillingAnOctantSeesAnEighthOfTheSphere) {
  EXPECT_NEAR(triangleSolidAngle({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 4 * kPi / 8, 1e-12);
  EXPECT_NEAR(triangleSolidAngle({1, 0, 0}, {0, 0, 1}, {0, 1, 0}), -4 * kPi / 8, 1e-12);
}

TEST(SolidAngle, SummedOverACubeItIsTheWindingNumber) {
  for (const Vec3& inside : {Vec3{0.5, 0.5, 0.5}, Vec3{0.01, 0.99, 0.5}, Vec3{0.999, 0.001, 0.999}}) {
    EXPECT_NEAR(cubeWindingNumber(inside, false), 1, 1e-9);
    EXPECT_NEAR(cubeWindingNumber(inside, true), -1, 1e-9);
  }
  for (const Vec3& outside : {Vec3{1.5, 0.5, 0.5}, Vec3{-0.01, 0.5, 0.5}, Vec3{10, -10, 3}}) {
    EXPECT_NEAR(cubeWindingNumber(outside, false), 0, 1e-9);
  }
}

TEST(SolidAngle, AViewpointInTheTrianglesPlaneSeesNothing) {
  EXPECT_EQ(triangleSolidAngle({1, 0, 0}, {0, 1, 0}, {2, 2, 0}), 0);
}

}  // namespace
}  // namespace thintool
