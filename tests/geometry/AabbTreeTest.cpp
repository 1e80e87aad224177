// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/AabbTree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace thintool {
namespace {

std::vector<Aabb> randomBoxes(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> position(-10, 10);
  std::uniform_real_distribution<Real> size(0, 0.5);
  std::vector<Aabb> boxes;
  for (int i = 0; i < count; ++i) {
    const Vec3 low{position(random), position(random), position(random)};
    boxes.push_back({low, low + Vec3{size(random), size(random), size(random)}});
  }
  return boxes;
}

TEST(AabbTree, OverlapQueryFindsExactlyTheBruteForceSet) {
  const std::vector<Aabb> boxes = randomBoxes(3000, 1);
  AabbTree tree;
  tree.build(boxes);
  for (const Aabb& query : randomBoxes(200, 2)) {
    const Aabb grown = query.expanded(0.7);
    std::vector<Index> found;
    tree.queryOverlap(grown, [&](Index item) { found.push_back(item); });
    std::vector<Index> expected;
    for (Index i = 0; i < boxes.size(); ++i) {
      if (boxes[i].overlaps(grown)) expected.push_back(i);
    }
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
  }
}

TEST(AabbTree, SegmentQueryFindsExactlyTheBruteForceSet) {
  const std::vector<Aabb> boxes = randomBoxes(3000, 3);
  AabbTree tree;
  tree.build(boxes);
  std::mt19937 random(4);
  std::uniform_real_distribution<Real> coordinate(-12, 12);
  for (int q = 0; q < 200; ++q) {
    const Vec3 origin{coordinate(random), coordinate(random), coordinate(random)};
    // Every fourth segment runs along an axis, exercising the infinite reciprocals.
    Vec3 delta{coordinate(random), coordinate(random), coordinate(random)};
    if (q % 4 == 0) delta = {0, 0, delta.z};
    const SegmentSlab slab(origin, delta);
    std::vector<Index> found;
    tree.querySegment(slab, [&](Index item) { found.push_back(item); });
    std::vector<Index> expected;
    for (Index i = 0; i < boxes.size(); ++i) {
      if (slab.overlaps(boxes[i])) expected.push_back(i);
    }
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
  }
}

TEST(AabbTree, SlabTestAgreesWithSampling) {
  const Aabb box{{0, 0, 0}, {1, 1, 1}};
  EXPECT_TRUE(SegmentSlab({-1, 0.5, 0.5}, {3, 0, 0}).overlaps(box));
  EXPECT_FALSE(SegmentSlab({-1, 1.5, 0.5}, {3, 0, 0}).overlaps(box));
  EXPECT_FALSE(SegmentSlab({-3, 0.5, 0.5}, {1, 0, 0}).overlaps(box));  // stops short
  EXPECT_TRUE(SegmentSlab({0.5, 0.5, 0.5}, {0, 0, 0}).overlaps(box));  // a point inside
}

TEST(AabbTree, EmptyTreeVisitsNothing) {
  AabbTree tree;
  tree.build({});
  int visits = 0;
  tree.queryOverlap({{-1, -1, -1}, {1, 1, 1}}, [&](Index) { ++visits; });
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(visits, 0);
}

}  // namespace
}  // namespace thintool
