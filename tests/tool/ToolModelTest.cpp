// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "tool/ToolModel.h"

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <algorithm>

namespace thintool {
namespace {

bool isOpposite(const ToolModel& model, Index node, Index other) {
  const auto begin = model.opposites.begin() + model.oppositeBegin[node];
  const auto end = model.opposites.begin() + model.oppositeBegin[node + 1];
  return std::find(begin, end, other) != end;
}

// A spatula blade, 0.1 wide (x), 0.01 thick (y), 0.04 long (z), whose long sides are wedges so
// steep that a node near the top of one side looks across the whole blade along its inward
// normal: the paper's Fig. 6. The two wedges differ, as a ground blade's do.
ConvexMesh spatula() {
  const Real a = 0.05, h = 0.005, w = 0.0003, c = 0.02;
  ConvexMesh mesh;
  // Counter-clockwise seen from +z.
  const Vec3 profile[6] = {{-a, -h, 0}, {a, -h, 0}, {a + w, 0, 0}, {a, h, 0}, {-a, h, 0}, {-a - 2 * w, 0.3 * h, 0}};
  for (int end = 0; end < 2; ++end) {
    for (const Vec3& p : profile) mesh.vertices.push_back({p.x, p.y, end == 0 ? -c : c});
  }
  // Sides of the prism (counter-clockwise seen from outside), then the two hexagonal ends.
  for (Index k = 0; k < 6; ++k) {
    const Index n = (k + 1) % 6;
    mesh.triangles.push_back({k, n, Index(n + 6)});
    mesh.triangles.push_back({k, Index(n + 6), Index(k + 6)});
  }
  for (Index k = 1; k + 1 < 6; ++k) {
    mesh.triangles.push_back({0, Index(k + 1), k});
    mesh.triangles.push_back({6, Index(k + 6), Index(k + 7)});
  }
  return mesh;
}

TEST(ToolModel, PlateGetsAGridOnEveryFaceAndMutualPairsAcrossItsThickness) {
  const ToolModel model = buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), {});
  EXPECT_NEAR(model.thickness, 0.02, 1e-12);
  EXPECT_NEAR(model.spacing, 0.1, 1e-12);
  // 8 × 8 cells on each large face, 8 × 1 on each narrow side.
  EXPECT_EQ(model.nodeCount(), 2u * 64 + 4 * 8);
  Index largeFaceNodes = 0;
  for (Index i = 0; i < model.nodeCount(); ++i) {
    const bool largeFace = std::abs(model.normals[i].y) > 0.5;
    if (!largeFace) {
      // The narrow sides are 0.8 apart, beyond the 0.03 association ray: no partner.
      EXPECT_EQ(model.partners[i], kInvalidIndex);
      continue;
    }
    ++largeFaceNodes;
    const Index partner = model.partners[i];
    ASSERT_NE(partner, kInvalidIndex);
    EXPECT_EQ(model.partners[partner], i) << "box pairs are mutual";
    EXPECT_NEAR(dot(model.normals[partner], model.normals[i]), -1, 1e-12);
    EXPECT_NEAR(length(model.positions[partner] - model.positions[i]), 0.02, 1e-9);
    EXPECT_NEAR(model.probeLengths[i], 0.02, 1e-12);
  }
  EXPECT_EQ(model.mutualPairs, largeFaceNodes);
  EXPECT_EQ(model.featureEdges.size(), 12u) << "a box has 12 edges; its face diagonals are not edges";
  ASSERT_EQ(model.featureEdgeNormals.size(), model.featureEdges.size());
  for (std::size_t e = 0; e < model.featureEdges.size(); ++e) {
    const std::array<Vec3, 2>& sides = model.featureEdgeNormals[e];
    EXPECT_NEAR(dot(sides[0], sides[1]), 0, 1e-12) << "a box's edge joins two perpendicular faces";
    for (const Vec3& normal : sides) {
      // Both ends of the edge lie on the face: as far along its normal as the box reaches.
      Real farthest = -1;
      for (const Vec3& corner : model.mesh.vertices) farthest = std::max(farthest, dot(normal, corner));
      for (Index end : model.featureEdges[e]) EXPECT_NEAR(dot(normal, model.mesh.vertices[end]), farthest, 1e-12);
    }
  }
}

TEST(ToolModel, BoxFaceGridSamplesOnlyTheTwoLargeFaces) {
  ToolModelSettings settings;
  settings.sampling.layout = SamplingLayout::BoxFaceGrid;
  settings.sampling.spacing = 0.05;
  const ToolModel model = buildToolModel(makeBoxMesh({0.4, 0.01, 0.2}), settings);
  EXPECT_EQ(model.nodeCount(), 2u * 16 * 8);
  for (Index i = 0; i < model.nodeCount(); ++i) {
    EXPECT_EQ(std::abs(model.normals[i].y), 1);
    EXPECT_EQ(model.partners[model.partners[i]], i);
  }
  EXPECT_THROW(buildToolModel(spatula(), settings), Error);
}

TEST(ToolModel, PaperLayoutPutsOneNodePerHullTriangle) {
  ToolModelSettings settings;
  settings.sampling.layout = SamplingLayout::HullTriangleCentroids;
  const ToolModel model = buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), settings);
  EXPECT_EQ(model.nodeCount(), 12u);
}

TEST(ToolModel, SpatulaPairsAreNotMutualAndTheLimitedRayKeepsThemFromCrossingTheBlade) {
  const ConvexMesh blade = spatula();
  ToolModelSettings limited;  // association ray: 1.5 × thickness
  const ToolModel model = buildToolModel(blade, limited);
  ToolModelSettings unlimited;
  unlimited.association.maxRayLength = 1;
  const ToolModel across = buildToolModel(blade, unlimited);
  ASSERT_EQ(model.nodeCount(), across.nodeCount());

  auto longestPair = [](const ToolModel& m) {
    Real longest = 0;
    for (Index i = 0; i < m.nodeCount(); ++i) {
      if (m.partners[i] != kInvalidIndex) {
        longest = std::max(longest, length(m.positions[m.partners[i]] - m.positions[i]));
      }
    }
    return longest;
  };
  // Unlimited, a node near the top of a steep side pairs with one across the blade (Fig. 6).
  EXPECT_GT(longestPair(across), 5 * across.thickness);
  // Limited, no pair reaches farther than the ray plus the width of one patch.
  EXPECT_LT(longestPair(model), 1.5 * model.thickness + model.spacing);
  EXPECT_GT(model.unpairedNodes, across.unpairedNodes);

  // The pairs across the blade are not mutual (the partner pairs with a node on its own side),
  // and the opposite sets hold both directions of every pair, so check 1 blocks either way.
  EXPECT_LT(across.mutualPairs, across.nodeCount() - across.unpairedNodes);
  for (const ToolModel* m : {&model, &across}) {
    for (Index i = 0; i < m->nodeCount(); ++i) {
      const Index partner = m->partners[i];
      if (partner == kInvalidIndex) continue;
      EXPECT_TRUE(isOpposite(*m, i, partner));
      EXPECT_TRUE(isOpposite(*m, partner, i)) << "node " << partner << " must block " << i << " too";
    }
  }
}

TEST(ToolModel, WithoutAssociationThereAreNoPairsAndNoOpposites) {
  ToolModelSettings settings;
  settings.association.enabled = false;
  const ToolModel model = buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), settings);
  EXPECT_TRUE(std::all_of(model.partners.begin(), model.partners.end(), [](Index p) { return p == kInvalidIndex; }));
  EXPECT_TRUE(model.opposites.empty());
}

TEST(ToolModel, SpacingSetsTheDensityAndTheCapStopsRunawaySampling) {
  ToolModelSettings fine;
  fine.sampling.spacing = 0.05;
  EXPECT_EQ(buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), fine).nodeCount(), 2u * 256 + 4 * 16);
  ToolModelSettings millimetresTypedAsMetres;
  millimetresTypedAsMetres.sampling.spacing = 1e-5;
  EXPECT_THROW(buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), millimetresTypedAsMetres), Error);
  // More cells than an index can count (the fuzzer's find): refused, not overflowed.
  ToolModelSettings tiny;
  tiny.sampling.spacing = 1e-9;
  EXPECT_THROW(buildToolModel(makeBoxMesh({1e3, 1, 1e3}), tiny), Error);
  tiny.sampling.layout = SamplingLayout::BoxFaceGrid;
  EXPECT_THROW(buildToolModel(makeBoxMesh({1e3, 1, 1e3}), tiny), Error);
}

TEST(ToolModel, InvalidInputIsAnErrorNotACrash) {
  ToolModelSettings negative;
  negative.sampling.spacing = -1;
  EXPECT_THROW(buildToolModel(makeBoxMesh({1, 1, 1}), negative), Error);
  // Zero is a length the user gave, not a request for the automatic one.
  ToolModelSettings zeroRay;
  zeroRay.association.maxRayLength = 0;
  EXPECT_THROW(buildToolModel(makeBoxMesh({1, 1, 1}), zeroRay), Error);
  ToolModelSettings zeroProbe;
  zeroProbe.probeDepth = 0;
  EXPECT_THROW(buildToolModel(makeBoxMesh({1, 1, 1}), zeroProbe), Error);
  EXPECT_THROW(buildToolModel(ConvexMesh{}, {}), Error);
  try {
    buildToolModel(makeBoxMesh({1, 0, 1}), {});
    FAIL() << "a flat box is not a tool";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("invalid convex shape"), std::string::npos);
  }
}

}  // namespace
}  // namespace thintool
