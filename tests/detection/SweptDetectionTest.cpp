// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Swept detection on one soft face and a needle-like box, in the tool's frame: the face's motion
// over the step, and the soft solver's move of it since detection last left it.

#include "detection/SweptDetection.h"

#include <gtest/gtest.h>

namespace thintool {
namespace {

constexpr Real kHalfLength = 0.5;
constexpr Real kHalfWidth = 0.01;
constexpr Real kSkin = 0.002;

class OneFace : public ::testing::Test {
 protected:
  OneFace() : m_model(buildToolModel(makeBoxMesh({kHalfLength, kHalfWidth, kHalfWidth}), ToolModelSettings())) {
    m_memory.resize(3, 1);
  }

  // A face across the needle's end, at x; its corners lie well outside the needle's section.
  static std::vector<Vec3> faceAt(Real x) { return {{x, 0.1, -0.1}, {x, -0.1, -0.1}, {x, 0, 0.15}}; }

  // One step of the face from start to end, the solver having moved it from checked to start since
  // detection last saw it.
  std::vector<PatchContact> step(const std::vector<Vec3>& checked, const std::vector<Vec3>& start,
                            const std::vector<Vec3>& end) {
    SoftPatch patch;
    patch.positions = end;
    patch.previousPositions = start;
    patch.checkedPositions = checked;
    patch.inverseMasses = {1, 1, 1};
    patch.nodeIds = {0, 1, 2};
    patch.faces = {{0, 1, 2}};
    patch.faceIds = {0};
    const Pose still;
    DetectionResult result;
    detectSwept({m_model, still, still, 0.01, kSkin}, patch, m_memory, m_work, result);
    return result.contacts;
  }

  // Whether the contacts hold the face beyond the needle's end, on the +x side, the skin away.
  static bool holdBeyondTheEnd(const std::vector<PatchContact>& contacts) {
    bool any = false;
    for (const PatchContact& contact : contacts) {
      EXPECT_EQ(contact.kind, ContactKind::ToolPoint);
      EXPECT_GT(contact.normal.x, 0.99);
      EXPECT_NEAR(-contact.offset / contact.normal.x, kHalfLength + kSkin, 1e-9);
      any = true;
    }
    return any;
  }

  ToolModel m_model;
  SideMemory m_memory;
  SweptWorkspace m_work;
};

TEST_F(OneFace, AFaceSweptOverTheNeedlesEndIsHeldBeyondIt) {
  EXPECT_TRUE(holdBeyondTheEnd(step(faceAt(0.6), faceAt(0.6), faceAt(0.45))));
}

// Detection sweeps a face only over the step, not over the soft solver's own move since detection
// last left it, as it does for the nodes: a face the solver carries over the needle's end corners,
// with none of its nodes entering, is caught after the solver, by the last word
// (tests/response/SeparationTest.cpp, AFaceTheSolverCarriedOverTheNeedlesEndGoesBackBeyondIt).

TEST_F(OneFace, AFaceThatStaysBeyondTheSkinIsLeftAlone) {
  EXPECT_TRUE(step(faceAt(0.60), faceAt(0.55), faceAt(0.55)).empty());
  EXPECT_TRUE(step(faceAt(0.60), faceAt(0.51), faceAt(0.503)).empty());
  EXPECT_FALSE(step(faceAt(0.60), faceAt(0.51), faceAt(0.501)).empty()) << "within the skin at the end";
}

TEST_F(OneFace, ANodeTheSolverSlidAlongTheGrownEndWithinRoundingDidNotEnter) {
  // The solver's holds keep a node on the needle's end grown by the skin (x = 0.502), up to
  // rounding: one slid there from above the needle down to its axis, then moved clear, has not
  // entered from above, and nothing sends it over the needle.
  const Real grownEnd = kHalfLength + kSkin;
  const auto face = [](const Vec3& onAxis, Real x) {
    return std::vector<Vec3>{onAxis, {x, 0.1, -0.1}, {x, -0.1, -0.1}};
  };
  const std::vector<Vec3> checked = face({grownEnd + 1e-9, 0.03, 0}, 0.51);
  const std::vector<Vec3> end = face({0.51, 0, 0}, 0.51);
  EXPECT_TRUE(step(checked, face({grownEnd - 1e-9, 0, 0}, 0.51), end).empty());
  // Slid 10 um inside the grown end, it did enter, through the grown top face it came down past,
  // and goes back out that way.
  m_memory.forget();
  const std::vector<PatchContact> entered = step(checked, face({grownEnd - 1e-5, 0, 0}, 0.51), end);
  ASSERT_FALSE(entered.empty());
  EXPECT_EQ(entered[0].kind, ContactKind::SoftNode);
  EXPECT_GT(entered[0].normal.y, 0.99);
}

// A box 20 cm across that turns 164° in the step about its centre, and a soft node at rest 26 cm
// from that centre, beyond every corner. Seen from the box the node moves along an arc that never
// comes near it, and along the arc's chord, which passes 3.6 cm from the centre, through the box.
// Reading the chord, detection pushes the node out of a box it never met; following the arc it
// leaves it alone.
TEST(SweptDetection, ANodeBesideASpinningToolIsLeftAloneWhenTheArcIsFollowed) {
  const ToolModel box = buildToolModel(makeBoxMesh({0.1, 0.1, 0.1}), ToolModelSettings());
  const Real turn = 164 * kPi / 180;
  Pose turned;
  turned.rotation = rotationAboutAxis({0, 0, 1}, turn);
  const Vec3 node = rotationAboutAxis({0, 0, 1}, turn / 2) * Vec3{0.26, 0, 0};
  SoftPatch patch;
  patch.positions = {node};
  patch.previousPositions = {node};
  patch.inverseMasses = {1};
  patch.nodeIds = {0};
  const auto contactsWith = [&](Real maxTurnPerSample) {
    SideMemory memory;
    memory.resize(1, 0);
    SweptWorkspace work;
    DetectionResult result;
    detectSwept({box, Pose{}, turned, 0.01, 0.01, 1, Pose{}, maxTurnPerSample}, patch, memory, work, result);
    return result.contacts.size();
  };
  EXPECT_EQ(contactsWith(0), 1U) << "the chord passes through the box";
  EXPECT_EQ(contactsWith(5 * kPi / 180), 0U);
}

}  // namespace
}  // namespace thintool
