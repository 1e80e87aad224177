// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The paper's Fig. 4 as a scripted sequence, and its Fig. 7 (right) ablation: a 0.02 m plate
// comes down onto a soft ball of radius 1 (1280 faces) whose top is at y = 1.

#include "TestMeshes.h"

#include "detection/Detection.h"

#include <gtest/gtest.h>

namespace thintool {
namespace {

constexpr Real kHalfThickness = 0.01;
constexpr Real kSkin = 0.005;
constexpr Real kDt = 0.01;

struct Step {
  Index colliding = 0;
  Index pushingUp = 0;    // contacts that push the cap up, through the plate it came under
  Index pushingDown = 0;  // contacts that push it back down, to the side it came from
  DetectionCounters counters;
};

class Fig4Sequence : public ::testing::Test {
 protected:
  Fig4Sequence() : m_ball(test::icosphere(1, {0, 0, 0}, 3)), m_patch(test::patchOf(m_ball)), m_query(m_patch) {}

  void build(bool association) {
    ToolModelSettings settings;
    settings.association.enabled = association;
    m_model = buildToolModel(makeBoxMesh({0.4, kHalfThickness, 0.4}), settings);
    m_history.reset();
  }

  // Places the plate so that the ball's top lies `depth` above the plate's underside.
  Step stepAt(Real depth, bool check1, bool check2) {
    Pose pose;
    pose.translation = {0, 1 - depth + kHalfThickness, 0};
    DetectionInput input;
    input.filters.check1 = check1;
    input.filters.check2 = check2;
    input.reverseRayLength = 3;
    input.reverseQuery = &m_query;
    Step step;
    detectContacts({m_model, pose, pose, kDt, kSkin}, m_patch, input, m_history, m_result);
    const std::vector<PatchContact>& contacts = m_result.contacts;
    step.counters = m_result.counters;
    step.colliding = static_cast<Index>(contacts.size());
    for (const PatchContact& c : contacts) {
      step.pushingUp += c.normal.y > 0.5 ? 1 : 0;
      step.pushingDown += c.normal.y < -0.5 ? 1 : 0;
      EXPECT_LE(c.depth, 2 * kHalfThickness + 1e-12);
      EXPECT_GE(c.depth, -kSkin - 1e-12);
    }
    return step;
  }

  ConvexMesh m_ball;
  SoftPatch m_patch;
  test::BruteForceRayQuery m_query;
  ToolModel m_model;
  PairHistory m_history;
  DetectionResult m_result;
};

TEST_F(Fig4Sequence, NoContactThenBottomNodesThenImmersedWithTopNodesExcluded) {
  build(true);
  const Step above = stepAt(-0.1, true, true);  // (1) the plate 0.1 above the ball
  EXPECT_EQ(above.counters.candidates, 0u);
  EXPECT_EQ(above.colliding, 0u);

  const Step touching = stepAt(0.004, true, true);  // (2) the cap 4 mm into the plate's underside
  EXPECT_GT(touching.pushingDown, 0u);
  EXPECT_EQ(touching.pushingUp, 0u);
  EXPECT_EQ(touching.colliding, touching.pushingDown);

  const Step immersed = stepAt(0.016, true, true);  // (3) the cap near the plate's top face
  EXPECT_GT(immersed.pushingDown, 0u);
  EXPECT_EQ(immersed.pushingUp, 0u) << "top nodes must be excluded";
  EXPECT_GT(immersed.counters.excludedByCheck1, 0u);
  // The nodes themselves, for display: as many as counted, each a node blocked by check 1.
  const std::vector<Index>& excluded = m_result.excludedNodes[0];
  EXPECT_EQ(excluded.size(), immersed.counters.excludedByCheck1);
  for (Index node : excluded) EXPECT_LT(node, m_model.nodeCount());
}

TEST_F(Fig4Sequence, RaysOnlyLetTheTopNodesPushTheCapThroughThePlate) {
  build(false);  // the paper's Fig. 7 (right): no association, no checks
  stepAt(-0.1, false, false);
  stepAt(0.004, false, false);
  const Step immersed = stepAt(0.016, false, false);
  EXPECT_GT(immersed.pushingDown, 0u);
  EXPECT_GT(immersed.pushingUp, 0u) << "the unfeasible contacts of Fig. 7 (right)";
}

TEST_F(Fig4Sequence, EachCheckAloneRemovesTheUnfeasibleContactsOfASlowPress) {
  // 2 mm a step, less than the skin: the underside meets every part of the cap first.
  for (int only = 1; only <= 2; ++only) {
    build(true);
    Step last;
    for (Real depth = -0.01; depth <= 0.0165; depth += 0.002) {
      last = stepAt(depth, only == 1, only == 2);
      EXPECT_EQ(last.pushingUp, 0u) << "check " << only << " alone, depth " << depth;
    }
    EXPECT_GT(last.pushingDown, 0u);
    EXPECT_GT(only == 1 ? last.counters.excludedByCheck1 : last.counters.excludedByCheck2, 0u);
  }
}

TEST_F(Fig4Sequence, CheckOneNeedsHistorySoAJumpStraightIntoTheBallNeedsCheckTwo) {
  // Without a previous step in contact, check 1 has nothing to block with: a plate that arrives
  // with the cap already past its mid-plane is only saved by check 2's orientation test.
  build(true);
  stepAt(-0.1, true, false);
  const Step jumpedCheck1Only = stepAt(0.016, true, false);
  EXPECT_GT(jumpedCheck1Only.pushingUp, 0u);

  build(true);
  stepAt(-0.1, true, true);
  const Step jumpedBoth = stepAt(0.016, true, true);
  EXPECT_EQ(jumpedBoth.pushingUp, 0u);
  EXPECT_GT(jumpedBoth.counters.excludedByCheck2, 0u);
}

TEST_F(Fig4Sequence, HistoryClearsWhenTheContactEnds) {
  build(true);
  stepAt(0.004, true, true);
  EXPECT_GT(m_history.blockedCount(), 0u);
  stepAt(-0.1, true, true);
  EXPECT_EQ(m_history.blockedCount(), 0u);
}

TEST(Detection, ContactsReportWhereTheRayMetTheFace) {
  // One big soft triangle 3 mm inside a plate's underside.
  SoftPatch patch;
  patch.positions = {{-1, 0.003, -1}, {1, 0.003, -1}, {0, 0.003, 2}};
  patch.previousPositions = patch.positions;
  patch.inverseMasses = {1, 1, 1};
  patch.nodeIds = {0, 1, 2};
  patch.faces = {{0, 2, 1}};  // facing up
  patch.faceIds = {7};
  patch.orientation = 1;
  ToolModelSettings settings;
  settings.sampling.spacing = 0.2;
  const ToolModel model = buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), settings);
  Pose pose;
  pose.translation = {0, 0.01, 0};  // underside at y = 0
  DetectionInput input;
  input.filters.reverseRay = false;  // an open triangle: nothing behind it
  PairHistory history;
  DetectionResult result;
  detectContacts({model, pose, pose, 0.01, 0}, patch, input, history, result);
  const std::vector<PatchContact>& contacts = result.contacts;
  const DetectionCounters& counters = result.counters;
  ASSERT_EQ(contacts.size(), 4u);  // the 2 × 2 grid of the underside
  for (const PatchContact& c : contacts) {
    EXPECT_EQ(c.softFace, 7u);
    EXPECT_NEAR(c.depth, 0.003, 1e-12);
    EXPECT_NEAR(c.normal.y, -1, 1e-12);
    EXPECT_NEAR(c.point.y, 0.003, 1e-12);
    const Vec3 fromBarycentric = patch.positions[0] * c.barycentric.x + patch.positions[2] * c.barycentric.y +
                                 patch.positions[1] * c.barycentric.z;
    EXPECT_LT(length(fromBarycentric - c.point), 1e-12);
  }
  EXPECT_EQ(counters.colliding, 4u);
  EXPECT_NEAR(counters.maxDepth, 0.003, 1e-12);
}

TEST(Detection, NonFiniteSoftFacesAreSkippedAndCounted) {
  SoftPatch patch = test::patchOf(test::icosphere(1, {0, 0, 0}, 1));
  patch.positions[0].x = std::numeric_limits<Real>::infinity();
  const ToolModel model = buildToolModel(makeBoxMesh({0.4, 0.01, 0.4}), {});
  Pose pose;
  pose.translation = {0, 0.995, 0};
  PairHistory history;
  DetectionResult result;
  test::BruteForceRayQuery query(patch);
  DetectionInput input;
  input.reverseQuery = &query;
  detectContacts({model, pose, pose, 0.01, 0}, patch, input, history, result);
  const std::vector<PatchContact>& contacts = result.contacts;
  const DetectionCounters& counters = result.counters;
  EXPECT_EQ(counters.skippedFaces, 5u);  // an icosahedron vertex has five faces
  for (const PatchContact& c : contacts) {
    EXPECT_TRUE(isFinite(c.point));
  }
}

}  // namespace
}  // namespace thintool
