// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/geometry/RayTriangle.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace thintool {
namespace {

constexpr Real kTolerance = 1e-12;

// The unit right triangle in the z = 0 plane.
const Vec3 kV0{0, 0, 0};
const Vec3 kV1{1, 0, 0};
const Vec3 kV2{0, 1, 0};

TEST(RayTriangle, HitsInteriorWithFractionAndBarycentrics) {
  const SegmentTriangleHit hit = intersectSegmentTriangle({0.25, 0.5, 2}, {0, 0, -4}, kV0, kV1, kV2);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.t, 0.5, kTolerance);
  EXPECT_NEAR(hit.u, 0.25, kTolerance);
  EXPECT_NEAR(hit.v, 0.5, kTolerance);
}

TEST(RayTriangle, IsTwoSided) {
  const SegmentTriangleHit fromBelow = intersectSegmentTriangle({0.2, 0.2, -1}, {0, 0, 2}, kV0, kV1, kV2);
  ASSERT_TRUE(fromBelow.hit);
  EXPECT_NEAR(fromBelow.t, 0.5, kTolerance);
}

TEST(RayTriangle, MissesBesideTheTriangle) {
  EXPECT_FALSE(intersectSegmentTriangle({0.8, 0.8, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
  EXPECT_FALSE(intersectSegmentTriangle({-0.1, 0.5, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
}

TEST(RayTriangle, MissesWhenTheSegmentStopsShortOrStartsBeyond) {
  EXPECT_FALSE(intersectSegmentTriangle({0.2, 0.2, 2}, {0, 0, -1}, kV0, kV1, kV2).hit);
  EXPECT_FALSE(intersectSegmentTriangle({0.2, 0.2, -0.5}, {0, 0, -1}, kV0, kV1, kV2).hit);
}

TEST(RayTriangle, EndpointsOnTheTriangleHitAtZeroAndOne) {
  const SegmentTriangleHit start = intersectSegmentTriangle({0.2, 0.2, 0}, {0, 0, 1}, kV0, kV1, kV2);
  ASSERT_TRUE(start.hit);
  EXPECT_EQ(start.t, 0);
  const SegmentTriangleHit end = intersectSegmentTriangle({0.2, 0.2, 1}, {0, 0, -1}, kV0, kV1, kV2);
  ASSERT_TRUE(end.hit);
  EXPECT_NEAR(end.t, 1, kTolerance);
}

TEST(RayTriangle, SharedEdgeHitsBothNeighbours) {
  // The square [0,1]² split along its diagonal; a segment straight through the diagonal.
  const Vec3 v3{1, 1, 0};
  const Vec3 origin{0.5, 0.5, 1};
  const Vec3 delta{0, 0, -2};
  EXPECT_TRUE(intersectSegmentTriangle(origin, delta, kV0, kV1, v3).hit);
  EXPECT_TRUE(intersectSegmentTriangle(origin, delta, kV0, v3, kV2).hit);
}

TEST(RayTriangle, VertexAndEdgeHitsCount) {
  EXPECT_TRUE(intersectSegmentTriangle({0, 0, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
  EXPECT_TRUE(intersectSegmentTriangle({1, 0, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
  EXPECT_TRUE(intersectSegmentTriangle({0.5, 0, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
  // Just outside an edge, by far more than the tolerance.
  EXPECT_FALSE(intersectSegmentTriangle({0.5, -1e-6, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
}

TEST(RayTriangle, ParallelSegmentsMissWithoutDividingByZero) {
  // In the triangle's plane, through its interior.
  EXPECT_FALSE(intersectSegmentTriangle({-1, 0.2, 0}, {3, 0, 0}, kV0, kV1, kV2).hit);
  // Parallel, above it.
  EXPECT_FALSE(intersectSegmentTriangle({-1, 0.2, 0.1}, {3, 0, 0}, kV0, kV1, kV2).hit);
}

TEST(RayTriangle, DegenerateInputMisses) {
  // Zero area: collinear and coincident corners.
  EXPECT_FALSE(intersectSegmentTriangle({0.5, 0, 1}, {0, 0, -2}, kV0, kV1, {2, 0, 0}).hit);
  EXPECT_FALSE(intersectSegmentTriangle({0, 0, 1}, {0, 0, -2}, kV0, kV0, kV0).hit);
  // Zero-length segment, even lying on the triangle.
  EXPECT_FALSE(intersectSegmentTriangle({0.2, 0.2, 0}, {0, 0, 0}, kV0, kV1, kV2).hit);
  // Not-a-number anywhere.
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_FALSE(intersectSegmentTriangle({nan, 0.2, 1}, {0, 0, -2}, kV0, kV1, kV2).hit);
  EXPECT_FALSE(intersectSegmentTriangle({0.2, 0.2, 1}, {0, 0, -2}, kV0, {nan, 0, 0}, kV2).hit);
}

TEST(RayTriangle, ScaleInvariantFromMicrometresToKilometres) {
  for (Real scale : {1e-6, 1e-3, 1.0, 1e3}) {
    const SegmentTriangleHit hit =
        intersectSegmentTriangle(Vec3{0.25, 0.25, 1} * scale, Vec3{0, 0, -2} * scale, kV0 * scale, kV1 * scale, kV2 * scale);
    ASSERT_TRUE(hit.hit) << "scale " << scale;
    EXPECT_NEAR(hit.t, 0.5, 1e-9) << "scale " << scale;
  }
}

TEST(RayTriangle, FarFromTheOriginStillExact) {
  const Vec3 offset{1e4, -1e4, 1e4};
  const SegmentTriangleHit hit =
      intersectSegmentTriangle(offset + Vec3{0.25, 0.25, 1}, {0, 0, -2}, offset + kV0, offset + kV1, offset + kV2);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.t, 0.5, 1e-9);
}

TEST(RayTriangle, HitPointLiesOnTheSegmentAndTheTriangle) {
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto randomPoint = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a = randomPoint(), b = randomPoint(), c = randomPoint();
    const Vec3 origin = randomPoint() * 2;
    const Vec3 delta = randomPoint() * 4;
    const SegmentTriangleHit hit = intersectSegmentTriangle(origin, delta, a, b, c);
    if (!hit.hit) {
      continue;
    }
    ++hits;
    const Vec3 onSegment = origin + delta * hit.t;
    const Vec3 onTriangle = a * (1 - hit.u - hit.v) + b * hit.u + c * hit.v;
    EXPECT_LT(length(onSegment - onTriangle), 1e-9);
  }
  EXPECT_GT(hits, 100);
}

}  // namespace
}  // namespace thintool
