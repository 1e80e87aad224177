// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/PointGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace thintool {
namespace {

std::vector<Index> bruteForce(const std::vector<Vec3>& points, const Aabb& box) {
  std::vector<Index> found;
  for (Index i = 0; i < points.size(); ++i) {
    if (box.contains(points[i])) found.push_back(i);
  }
  return found;
}

// The items the grid finds in box, each checked to come with its own point.
std::vector<Index> query(const PointGrid& grid, const std::vector<Vec3>& points, const Aabb& box) {
  std::vector<Index> found;
  grid.queryBox(box, [&](Index i, const Vec3& p) {
    EXPECT_EQ(p, points[i]) << "point " << i;
    found.push_back(i);
  });
  std::sort(found.begin(), found.end());
  return found;
}

// Every query box, small or large, inside, across or outside the set, finds exactly the points a
// loop over all of them finds.
void expectMatchesBruteForce(const std::vector<Vec3>& points, unsigned seed) {
  PointGrid grid;
  grid.build(points);
  Aabb bounds;
  for (const Vec3& p : points) bounds.include(p);
  const Vec3 centre = bounds.center();
  // Query boxes scaled to the set along each axis, so that flat and thin sets are hit too.
  const Real floor = std::max<Real>(length(bounds.extent()), 1e-3) / 20;
  const Vec3 scale{std::max(bounds.extent().x, floor), std::max(bounds.extent().y, floor),
                   std::max(bounds.extent().z, floor)};
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> offset(-1, 1);
  std::uniform_real_distribution<Real> size(0, 0.5);
  int nonEmpty = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 middle = centre + Vec3{offset(random) * scale.x, offset(random) * scale.y, offset(random) * scale.z} * 0.6;
    const Vec3 half{size(random) * scale.x, size(random) * scale.y, size(random) * scale.z};
    const Aabb box{middle - half, middle + half};
    const std::vector<Index> expected = bruteForce(points, box);
    nonEmpty += !expected.empty();
    ASSERT_EQ(query(grid, points, box), expected) << "query " << q;
  }
  EXPECT_GT(nonEmpty, 10) << "the queries must also find points";
  // A box exactly around one point finds it: the boundary counts.
  const Aabb onePoint = Aabb::fromPoints(points.back(), points.back());
  ASSERT_EQ(query(grid, points, onePoint), bruteForce(points, onePoint));
  EXPECT_FALSE(query(grid, points, onePoint).empty());
}

TEST(PointGrid, ScatteredPointsQueryLikeBruteForce) {
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> coordinate(-3, 5);
  std::vector<Vec3> points;
  for (int i = 0; i < 700; ++i) points.push_back({coordinate(random), coordinate(random), coordinate(random)});
  expectMatchesBruteForce(points, 1);
}

TEST(PointGrid, AFlatPlateAndALineGetOneLayerAndOneRow) {
  // A plate's two faces 2 cm apart, 17 × 17 nodes each, as ToolModel samples a 0.8 m plate.
  std::vector<Vec3> plate;
  for (int i = 0; i <= 16; ++i) {
    for (int k = 0; k <= 16; ++k) {
      plate.push_back({-0.4 + 0.05 * i, -0.01, -0.4 + 0.05 * k});
      plate.push_back({-0.4 + 0.05 * i, 0.01, -0.4 + 0.05 * k});
    }
  }
  expectMatchesBruteForce(plate, 2);
  PointGrid grid;
  grid.build(plate);
  EXPECT_LE(grid.cellCount(), 2 * plate.size()) << "about as many cells as points";
  EXPECT_GE(grid.cellCount(), plate.size() / 4) << "not one cell for everything";

  std::vector<Vec3> needle;  // points on a line: zero extent across it
  for (int i = 0; i < 100; ++i) needle.push_back({0.01 * i, 0.5, 0.5});
  expectMatchesBruteForce(needle, 3);
  grid.build(needle);
  EXPECT_LE(grid.cellCount(), 2 * needle.size());
}

TEST(PointGrid, DegenerateSetsAnswerQueries) {
  PointGrid grid;
  grid.build({});
  EXPECT_TRUE(grid.empty());
  EXPECT_TRUE(query(grid, {}, Aabb{{-1, -1, -1}, {1, 1, 1}}).empty());

  const std::vector<Vec3> same(5, Vec3{1, 2, 3});  // every point at one place
  grid.build(same);
  EXPECT_EQ(grid.cellCount(), 1u);
  EXPECT_EQ(query(grid, same, Aabb{{0, 0, 0}, {2, 2, 4}}).size(), 5u);
  EXPECT_TRUE(query(grid, same, Aabb{{0, 0, 0}, {0.5, 2, 4}}).empty());
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_TRUE(query(grid, same, Aabb{{nan, 0, 0}, {2, 2, 4}}).empty()) << "a box with NaN meets nothing";
}

}  // namespace
}  // namespace thintool
