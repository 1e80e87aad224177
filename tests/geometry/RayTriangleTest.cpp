// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/RayTriangle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

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

// The batched kernel against the scalar one: every lane's hit, t, u and v, bit for bit (misses
// are t = u = v = 0 in both), and empty lanes miss.

using Triangle = std::array<Vec3, 3>;

bool sameBits(Real a, Real b) {
  std::uint64_t x = 0;
  std::uint64_t y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

// Runs one segment against triangles (at most a block) with the scalar kernel and with every
// block kernel this CPU runs, the dispatched one too; returns the dispatched hit mask.
unsigned expectBlockAgrees(const Vec3& origin, const Vec3& delta, const std::vector<Triangle>& triangles) {
  TriangleBlock block;
  for (const Triangle& t : triangles) {
    EXPECT_TRUE(block.push(t[0], t[1], t[2]));
  }
  const auto expectLanesAgree = [&](const SegmentTriangleBlockHits& batch, const char* kernel) {
    for (int k = 0; k < TriangleBlock::kSize; ++k) {
      SegmentTriangleHit scalar;  // an empty lane: a miss
      if (k < static_cast<int>(triangles.size())) {
        const Triangle& t = triangles[static_cast<std::size_t>(k)];
        scalar = intersectSegmentTriangle(origin, delta, t[0], t[1], t[2]);
      }
      EXPECT_EQ(batch.hit(k), scalar.hit) << kernel << ", lane " << k;
      EXPECT_TRUE(sameBits(batch.t[k], scalar.t)) << kernel << ", lane " << k << ": t " << batch.t[k] << " vs "
                                                 << scalar.t;
      EXPECT_TRUE(sameBits(batch.u[k], scalar.u)) << kernel << ", lane " << k << ": u " << batch.u[k] << " vs "
                                                 << scalar.u;
      EXPECT_TRUE(sameBits(batch.v[k], scalar.v)) << kernel << ", lane " << k << ": v " << batch.v[k] << " vs "
                                                 << scalar.v;
    }
    EXPECT_EQ(batch.mask >> TriangleBlock::kSize, 0U) << kernel;
  };
  for (const BlockKernel kernel : availableBlockKernels()) {
    expectLanesAgree(intersectSegmentTriangleBlock(kernel, origin, delta, block), blockKernelName(kernel));
  }
  const SegmentTriangleBlockHits dispatched = intersectSegmentTriangleBlock(origin, delta, block);
  expectLanesAgree(dispatched, "dispatched");
  return dispatched.mask;
}

int hitCount(unsigned mask) {
  int count = 0;
  for (; mask != 0; mask &= mask - 1) {
    ++count;
  }
  return count;
}

TEST(RayTriangleBlock, HitsAndMissesAsTheScalarKernelOnTheUnitTriangle) {
  const std::vector<Triangle> unit{{kV0, kV1, kV2}};
  EXPECT_EQ(hitCount(expectBlockAgrees({0.25, 0.5, 2}, {0, 0, -4}, unit)), 1);
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, -1}, {0, 0, 2}, unit)), 1);   // from below
  EXPECT_EQ(hitCount(expectBlockAgrees({0.8, 0.8, 1}, {0, 0, -2}, unit)), 0);   // beside
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 2}, {0, 0, -1}, unit)), 0);   // stops short
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 0}, {0, 0, 1}, unit)), 1);    // starts on it
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 1}, {0, 0, -1}, unit)), 1);   // ends on it
}

TEST(RayTriangleBlock, EdgesAndVerticesAsTheScalarKernel) {
  // The square [0,1]² split along its diagonal, and segments through its corners, its edges'
  // midpoints and just outside them, within and beyond the tolerance.
  const Vec3 v3{1, 1, 0};
  const std::vector<Triangle> square{{kV0, kV1, v3}, {kV0, v3, kV2}, {kV0, kV1, kV2}};
  for (const Vec3& at : {kV0, kV1, kV2, v3, Vec3{0.5, 0.5, 0}, Vec3{0.5, 0, 0}, Vec3{0, 0.5, 0}, Vec3{1, 0.5, 0},
                         Vec3{0.5, -1e-10, 0}, Vec3{0.5, -1e-8, 0}, Vec3{0.5 + 1e-10, 0.5, 0}}) {
    expectBlockAgrees(at + Vec3{0, 0, 1}, {0, 0, -2}, square);
    expectBlockAgrees(at + Vec3{0.3, -0.2, 1}, {-0.6, 0.4, -2}, square);  // slanted through the same point
  }
  EXPECT_EQ(hitCount(expectBlockAgrees({0.5, 0.5, 1}, {0, 0, -2}, square)), 3);  // the diagonal: both halves and the unit triangle
}

TEST(RayTriangleBlock, ParallelAndDegenerateAsTheScalarKernel) {
  const std::vector<Triangle> triangles{
      {kV0, kV1, kV2},
      {kV0, kV1, Vec3{2, 0, 0}},  // collinear
      {kV0, kV0, kV0},            // a point
      {kV1, kV1, kV2},            // two corners coincide
      {Vec3{0, 0, 0.1}, Vec3{1, 0, 0.1}, Vec3{0, 1, 0.1}},
  };
  expectBlockAgrees({-1, 0.2, 0}, {3, 0, 0}, triangles);     // in the plane, through the interior
  expectBlockAgrees({-1, 0.2, 0.1}, {3, 0, 0}, triangles);   // in the second plane
  expectBlockAgrees({-1, 0.2, 0.05}, {3, 0, 0}, triangles);  // between the planes
  expectBlockAgrees({-1, 0.2, 0.05}, {3, 0, 1e-13}, triangles);  // all but parallel
  // Crosses the plane inside the first triangle, at a cosine of 2e-13: parallel by the rule.
  EXPECT_EQ(hitCount(expectBlockAgrees({0.1, 0.2, 1e-14}, {0.5, 0, -1e-13}, triangles)), 0);
  expectBlockAgrees({-1, 0.2, 0.05}, {3, 0, -0.1}, triangles);   // at a grazing angle
  expectBlockAgrees({0.2, 0.2, 0}, {0, 0, 0}, triangles);        // zero length, on the triangle
  expectBlockAgrees({0.5, 0, 1}, {0, 0, -2}, triangles);         // through the collinear one's line
}

TEST(RayTriangleBlock, NotANumberAndInfinityMissAsTheScalarKernel) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const std::vector<Triangle> triangles{
      {kV0, kV1, kV2},  {kV0, Vec3{nan, 0, 0}, kV2}, {Vec3{0, 0, inf}, kV1, kV2},
      {kV0, kV1, Vec3{0, -inf, 0}}, {kV0, kV1, kV2},
  };
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 1}, {0, 0, -2}, triangles)), 2);
  EXPECT_EQ(hitCount(expectBlockAgrees({nan, 0.2, 1}, {0, 0, -2}, triangles)), 0);
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 1}, {0, nan, -2}, triangles)), 0);
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, inf}, {0, 0, -2}, triangles)), 0);
  EXPECT_EQ(hitCount(expectBlockAgrees({0.2, 0.2, 1}, {0, 0, -inf}, triangles)), 0);
}

TEST(RayTriangleBlock, PartlyFilledBlocksMissInTheirEmptyLanes) {
  std::mt19937 random(11);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  for (int count = 0; count <= TriangleBlock::kSize; ++count) {
    for (int trial = 0; trial < 200; ++trial) {
      // Segments aimed through each triangle's centroid, so that most lanes hit.
      std::vector<Triangle> triangles;
      const Vec3 target = point() * 0.1;
      for (int k = 0; k < count; ++k) {
        triangles.push_back({target + point() * 0.5, target + point() * 0.5, target + point() * 0.5});
      }
      const Vec3 origin = target + point();
      expectBlockAgrees(origin, (target - origin) * 2, triangles);
    }
  }
  // A full block refuses a ninth triangle; clear() empties it.
  TriangleBlock block;
  for (int k = 0; k < TriangleBlock::kSize; ++k) {
    ASSERT_TRUE(block.push(kV0, kV1, kV2));
  }
  EXPECT_FALSE(block.push(kV0, kV1, kV2));
  EXPECT_EQ(intersectSegmentTriangleBlock({0.2, 0.2, 1}, {0, 0, -2}, block).mask, 0xFFU);
  block.clear();
  EXPECT_EQ(block.count, 0);
  EXPECT_EQ(intersectSegmentTriangleBlock({0.2, 0.2, 1}, {0, 0, -2}, block).mask, 0U);
}

TEST(RayTriangleBlock, AgreesWithTheScalarKernelOnRandomBlocks) {
  std::mt19937 random(13);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  std::uniform_int_distribution<int> kind(0, 9);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  int hits = 0;
  int edgeHits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 centre = point() * 0.2;
    const Vec3 origin = centre + point();
    // Mostly segments aimed near the block's centre; a tenth aimed at a corner or an edge of the
    // first triangle exactly, and a few parallel to it.
    std::vector<Triangle> triangles;
    for (int k = 0; k < TriangleBlock::kSize; ++k) {
      Triangle t{centre + point() * 0.3, centre + point() * 0.3, centre + point() * 0.3};
      switch (kind(random)) {
        case 0:
          t[2] = t[0] + (t[1] - t[0]) * coordinate(random);  // collinear
          break;
        case 1:
          t[1] = t[0];  // coincident corners
          break;
        case 2:
          if (k == 3) t[1].y = nan;
          break;
        default:
          break;
      }
      triangles.push_back(t);
    }
    const Triangle& first = triangles[0];
    Vec3 target = centre;
    Vec3 delta;
    switch (kind(random)) {
      case 0:
        target = first[1];  // a corner
        break;
      case 1:
        target = first[0] + (first[2] - first[0]) * 0.5;  // an edge's midpoint
        break;
      case 2:
        // In the first triangle's plane.
        delta = (first[1] - first[0]) * 3;
        break;
      default:
        break;
    }
    Vec3 start = origin;
    if (delta == Vec3{}) {
      delta = (target - origin) * (1 + 0.5 * coordinate(random));
    } else {
      start = first[0] - delta * 0.5 + (first[2] - first[0]) * 0.1;
    }
    const unsigned mask = expectBlockAgrees(start, delta, triangles);
    if (::testing::Test::HasFailure()) {
      FAIL() << "case " << i;
    }
    hits += hitCount(mask);
    if ((mask & 1U) != 0 && target != centre) {
      ++edgeHits;
    }
  }
  // The cases must exercise hits, corner and edge hits among them.
  EXPECT_GT(hits, 10000);
  EXPECT_GT(edgeHits, 1000);
}

TEST(RayTriangleBlock, DispatchesToTheWidestKernelTheCpuRuns) {
  const std::vector<BlockKernel>& kernels = availableBlockKernels();
  ASSERT_FALSE(kernels.empty());
  EXPECT_EQ(kernels.front(), BlockKernel::Portable);
  EXPECT_EQ(std::string(blockKernelName(BlockKernel::Avx512)), "avx512");
  // Ordered by width, so that the dispatch's choice, the last, is the widest.
  for (std::size_t k = 1; k < kernels.size(); ++k) {
    EXPECT_GT(static_cast<int>(kernels[k]), static_cast<int>(kernels[k - 1]));
  }
  // A kernel the CPU does not run answers as the portable one.
  TriangleBlock block;
  ASSERT_TRUE(block.push(kV0, kV1, kV2));
  for (const BlockKernel kernel : {BlockKernel::Portable, BlockKernel::Avx2, BlockKernel::Avx512}) {
    EXPECT_EQ(intersectSegmentTriangleBlock(kernel, {0.2, 0.2, 1}, {0, 0, -2}, block).mask, 1U)
        << blockKernelName(kernel);
  }
  std::printf("block kernels on this CPU:");
  for (const BlockKernel kernel : kernels) std::printf(" %s", blockKernelName(kernel));
  std::printf("\n");
}

}  // namespace
}  // namespace thintool
