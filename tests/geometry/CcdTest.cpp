// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/Ccd.h"
#include "geometry/RayTriangle.h"

#include <gtest/gtest.h>

#include <random>

namespace thintool {
namespace {

constexpr Real kTolerance = 1e-9;

TEST(ClipSegmentConvex, EntersThroughTheFaceItCrossesFirstAndLeavesThroughTheLast) {
  const ConvexMesh plate = makeBoxMesh({0.4, 0.01, 0.4});
  const std::vector<Plane> planes = facePlanes(plate);
  // Straight up through the plate, from 0.05 below to 0.05 above.
  const ClipResult through = clipSegmentConvex(planes, 0, {0.1, -0.05, 0}, {0.1, 0.05, 0});
  ASSERT_TRUE(through.hit);
  EXPECT_NEAR(through.enter, 0.4, kTolerance);
  EXPECT_NEAR(through.leave, 0.6, kTolerance);
  ASSERT_NE(through.enterPlane, kInvalidIndex);
  EXPECT_NEAR(planes[through.enterPlane].normal.y, -1, kTolerance);
  // Grown by a 0.02 skin, it enters earlier.
  EXPECT_NEAR(clipSegmentConvex(planes, 0.02, {0.1, -0.05, 0}, {0.1, 0.05, 0}).enter, 0.2, kTolerance);
  ASSERT_NE(through.leavePlane, kInvalidIndex);
  EXPECT_NEAR(planes[through.leavePlane].normal.y, 1, kTolerance);
  // Starting inside: no entry face.
  const ClipResult inside = clipSegmentConvex(planes, 0, {0.1, 0, 0}, {0.1, 0.05, 0});
  ASSERT_TRUE(inside.hit);
  EXPECT_EQ(inside.enterPlane, kInvalidIndex);
  EXPECT_NEAR(planes[inside.leavePlane].normal.y, 1, kTolerance);
  // Ending inside: no leaving face.
  EXPECT_EQ(clipSegmentConvex(planes, 0, {0.1, -0.05, 0}, {0.1, 0, 0}).leavePlane, kInvalidIndex);
  // Round the +x rim: in through the underside, out through the side.
  const ClipResult corner = clipSegmentConvex(planes, 0, {0.35, -0.05, 0}, {0.45, 0.05, 0});
  ASSERT_TRUE(corner.hit);
  EXPECT_NEAR(planes[corner.enterPlane].normal.y, -1, kTolerance);
  EXPECT_NEAR(planes[corner.leavePlane].normal.x, 1, kTolerance);
  // Beside the plate.
  EXPECT_FALSE(clipSegmentConvex(planes, 0, {0.5, -0.05, 0}, {0.5, 0.05, 0}).hit);
}

TEST(PointTriangleCcd, FindsTheMomentATriangleSweepsOverAPoint) {
  // A horizontal triangle falling from y = 1 to y = -1 past the origin.
  const Vec3 a{-1, 0, -1}, b{1, 0, -1}, c{0, 0, 1};
  const Vec3 up{0, 1, 0};
  const PointTriangleCcd hit = pointTriangleCcd({0, 0, 0}, a + up, b + up, c + up, a - up, b - up, c - up);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.t, 0.5, kTolerance);
  EXPECT_NEAR(hit.barycentric.x + hit.barycentric.y + hit.barycentric.z, 1, kTolerance);
  // Beside it: no hit.
  EXPECT_FALSE(pointTriangleCcd({3, 0, 0}, a + up, b + up, c + up, a - up, b - up, c - up).hit);
  // Stopping short: no hit.
  EXPECT_FALSE(pointTriangleCcd({0, 0, 0}, a + up, b + up, c + up, a + up * 0.5, b + up * 0.5, c + up * 0.5).hit);
  // Touching exactly at the end of the step.
  const PointTriangleCcd touch = pointTriangleCcd({0, 0, 0}, a + up, b + up, c + up, a, b, c);
  ASSERT_TRUE(touch.hit);
  EXPECT_NEAR(touch.t, 1, kTolerance);
}

TEST(PointTriangleCcd, TiltingTriangleAndSlidingInItsPlane) {
  // One corner rises from (0, 0, 1) to (0, 2, 1): the triangle tilts about its far edge and
  // sweeps over (0, 0.5, 0.5) when y = t·(z + 1), at t = 1/3.
  const Vec3 a{-1, 0, -1}, b{1, 0, -1}, c{0, 0, 1};
  const PointTriangleCcd tilting = pointTriangleCcd({0, 0.5, 0.5}, a, b, c, a, b, {0, 2, 1});
  ASSERT_TRUE(tilting.hit);
  EXPECT_NEAR(tilting.t, 1.0 / 3, kTolerance);
  // Sliding within its own plane onto a point lying in that plane.
  const PointTriangleCcd sliding = pointTriangleCcd({5, 0, 0}, a, b, c, a + Vec3{5, 0, 0}, b + Vec3{5, 0, 0},
                                                    c + Vec3{5, 0, 0});
  EXPECT_TRUE(sliding.hit);
}

TEST(EdgeEdgeCcd, FindsTheMomentAnEdgeSweepsAcrossAnother) {
  // Static edge along x; a z-aligned edge falls across it.
  const Vec3 p0{-1, 0, 0}, p1{1, 0, 0};
  const EdgeEdgeCcd hit = edgeEdgeCcd(p0, p1, {0.25, 1, -1}, {0.25, 1, 1}, {0.25, -1, -1}, {0.25, -1, 1});
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.t, 0.5, kTolerance);
  EXPECT_NEAR(hit.u, 0.625, kTolerance);
  EXPECT_NEAR(hit.s, 0.5, kTolerance);
  // Falling past the end of the static edge.
  EXPECT_FALSE(edgeEdgeCcd(p0, p1, {2, 1, -1}, {2, 1, 1}, {2, -1, -1}, {2, -1, 1}).hit);
  // Parallel, passing by above.
  EXPECT_FALSE(edgeEdgeCcd(p0, p1, {-1, 1, 0.5}, {1, 1, 0.5}, {-1, -1, 0.5}, {1, -1, 0.5}).hit);
  // Parallel and sweeping through it.
  EXPECT_TRUE(edgeEdgeCcd(p0, p1, {-1, 1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, -1, 0}).hit);
}

// Sign changes of the point's distance to the triangle's plane, found by fine sampling, with the
// point inside the triangle at the crossing, must all be found by the query: no false negatives.
TEST(PointTriangleCcd, NeverMissesACrossingThatSamplingFinds) {
  std::mt19937 random(11);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  int crossings = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 p = point() * 0.3;
    const Vec3 a0 = point(), b0 = point(), c0 = point();
    const Vec3 a1 = point(), b1 = point(), c1 = point();
    bool sampled = false;
    constexpr int kSamples = 400;
    Real previous = 0;
    for (int k = 0; k <= kSamples && !sampled; ++k) {
      const Real t = Real(k) / kSamples;
      const Vec3 a = a0 + (a1 - a0) * t, b = b0 + (b1 - b0) * t, c = c0 + (c1 - c0) * t;
      const Real distance = dot(normalizedOrZero(triangleNormal(a, b, c)), p - a);
      if (k > 0 && (distance < 0) != (previous < 0)) {
        Vec3 barycentric;
        if (projectOntoTriangle(p, a, b, c, barycentric) && barycentric.x > 0.01 && barycentric.y > 0.01 &&
            barycentric.z > 0.01) {
          sampled = true;
        }
      }
      previous = distance;
    }
    if (sampled) {
      ++crossings;
      EXPECT_TRUE(pointTriangleCcd(p, a0, b0, c0, a1, b1, c1).hit) << "trial " << trial;
    }
  }
  EXPECT_GT(crossings, 50);
}

TEST(EdgeEdgeCcd, NeverMissesACrossingThatSamplingFinds) {
  std::mt19937 random(12);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  int crossings = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 p0 = point(), p1 = point();
    const Vec3 e0a = point(), e1a = point(), e0b = point(), e1b = point();
    bool sampled = false;
    constexpr int kSamples = 400;
    Real previous = 0;
    for (int k = 0; k <= kSamples && !sampled; ++k) {
      const Real t = Real(k) / kSamples;
      const Vec3 q0 = e0a + (e0b - e0a) * t, q1 = e1a + (e1b - e1a) * t;
      const Real side = dot(p1 - p0, cross(q0 - p0, q1 - p0));
      if (k > 0 && (side < 0) != (previous < 0)) {
        Real u = 0, s = 0;
        closestPointsOfSegments(p0, p1, q0, q1, u, s);
        if (u > 0.01 && u < 0.99 && s > 0.01 && s < 0.99 &&
            length((p0 + (p1 - p0) * u) - (q0 + (q1 - q0) * s)) < 1e-2) {
          sampled = true;
        }
      }
      previous = side;
    }
    if (sampled) {
      ++crossings;
      EXPECT_TRUE(edgeEdgeCcd(p0, p1, e0a, e1a, e0b, e1b).hit) << "trial " << trial;
    }
  }
  EXPECT_GT(crossings, 50);
}

TEST(TriangleProjector, RecoversThePointsItWasBuiltFromAndRefusesALine) {
  const Vec3 a{0.3, -0.2, 1.0}, b{1.4, 0.1, 0.9}, c{0.2, 0.8, 1.3};
  const TriangleProjector projector(a, b, c);
  const Vec3 normal = cross(b - a, c - a);
  for (const Vec3& weights : {Vec3{1, 0, 0}, Vec3{0.2, 0.5, 0.3}, Vec3{-0.5, 1.25, 0.25}}) {
    // Off the plane along the normal: the projection is the weighted point itself.
    const Vec3 p = a * weights.x + b * weights.y + c * weights.z + normal * 0.7;
    Vec3 found;
    ASSERT_TRUE(projector.project(p, found));
    EXPECT_NEAR(found.x, weights.x, 1e-12);
    EXPECT_NEAR(found.y, weights.y, 1e-12);
    EXPECT_NEAR(found.z, weights.z, 1e-12);
  }
  Vec3 unused;
  EXPECT_FALSE(TriangleProjector({0, 0, 0}, {1, 2, 3}, {2, 4, 6}).project(a, unused));  // a line
  EXPECT_FALSE(TriangleProjector().project(a, unused));
}

}  // namespace
}  // namespace thintool
