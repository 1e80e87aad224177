// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/response/Response.h>

#include <gtest/gtest.h>

namespace thintool {
namespace {

// A plate's underside at y = 0 and one soft triangle 3 mm inside it, hit by one node.
struct Fixture {
  ToolModel model;
  Pose pose;
  SoftPatch patch;
  std::vector<Contact> contacts;

  Fixture() {
    ToolModelSettings settings;
    settings.sampling.spacing = 0.4;
    model = buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), settings);
    pose.translation = {0, 0.01, 0};
    patch.positions = {{-0.1, 0.003, -0.1}, {0.1, 0.003, -0.1}, {0, 0.003, 0.1}};
    patch.inverseMasses = {2, 2, 0};  // the third node is pinned
    patch.nodeIds = {0, 1, 2};
    patch.faces = {{0, 2, 1}};
    patch.faceIds = {0};
    Index bottomNode = 0;
    while (model.normals[bottomNode].y > -0.5) ++bottomNode;
    Contact contact;
    contact.toolNode = bottomNode;
    contact.patchFace = 0;
    contact.barycentric = {0.25, 0.25, 0.5};
    contact.depth = 0.003;
    contact.normal = {0, -1, 0};
    contacts.push_back(contact);
  }
};

constexpr Real kSkin = 0.001;
constexpr Real kDt = 0.01;

TEST(Response, ConstraintMovesTheFacesNodesToTheSkinOnTheEntrySide) {
  Fixture f;
  ResponseSettings settings;
  ResponseWorkspace workspace;
  std::vector<NodeCorrection> corrections;
  Wrench wrench;
  computeResponse(f.model, f.pose, f.patch, f.contacts, kSkin, kDt, settings, workspace, corrections, wrench);
  ASSERT_EQ(corrections.size(), 2u) << "the pinned node stays";
  Vec3 expectedForce;
  for (const NodeCorrection& c : corrections) {
    EXPECT_NE(c.vertex, 2u);
    EXPECT_NEAR(c.displacement.y, -(0.003 + kSkin), 1e-12);
    EXPECT_EQ(c.displacement.x, 0);
    const Vec3 moved = f.patch.positions[c.vertex] + c.displacement;
    EXPECT_NEAR(dot(moved, c.planeNormal) + c.planeOffset, 0, 1e-12);
    expectedForce -= c.displacement / (f.patch.inverseMasses[c.vertex] * kDt * kDt);
  }
  EXPECT_NEAR(wrench.force.y, expectedForce.y, 1e-9);
  EXPECT_GT(wrench.force.y, 0) << "the tissue pushes the tool up";
}

TEST(Response, ConstraintLeavesNodesAlreadyOutside) {
  Fixture f;
  for (Vec3& p : f.patch.positions) p.y = -0.002;  // below the skin already
  ResponseWorkspace workspace;
  std::vector<NodeCorrection> corrections;
  Wrench wrench;
  computeResponse(f.model, f.pose, f.patch, f.contacts, kSkin, kDt, {}, workspace, corrections, wrench);
  EXPECT_TRUE(corrections.empty());
  EXPECT_EQ(wrench.force.y, 0);
}

TEST(Response, PaperForceIsKTimesDepthSpreadByBarycentricWeights) {
  Fixture f;
  ResponseSettings settings;
  settings.kind = ResponseKind::PaperForce;
  settings.stiffness = 200;
  ResponseWorkspace workspace;
  std::vector<NodeCorrection> corrections;
  Wrench wrench;
  computeResponse(f.model, f.pose, f.patch, f.contacts, kSkin, kDt, settings, workspace, corrections, wrench);
  const Real force = 200 * (0.003 + kSkin);  // f = k·t, t measured into the skin
  ASSERT_EQ(corrections.size(), 2u);
  for (const NodeCorrection& c : corrections) {
    // The face's corners are (0, 2, 1): vertex 0 carries weight x, vertex 1 weight z.
    const Real weight = c.vertex == 0 ? 0.25 : 0.5;
    EXPECT_NEAR(c.displacement.y, -force * weight * f.patch.inverseMasses[c.vertex] * kDt * kDt, 1e-15);
  }
  EXPECT_NEAR(wrench.force.y, force * 0.75, 1e-9) << "the pinned node's share goes nowhere";
}

TEST(Response, NoneMovesNothing) {
  Fixture f;
  ResponseSettings settings;
  settings.kind = ResponseKind::None;
  ResponseWorkspace workspace;
  std::vector<NodeCorrection> corrections;
  Wrench wrench;
  computeResponse(f.model, f.pose, f.patch, f.contacts, kSkin, kDt, settings, workspace, corrections, wrench);
  EXPECT_TRUE(corrections.empty());
}

TEST(Response, ARimNodeEndsOutsideBothFacesThatHitIt) {
  Fixture f;
  // A second contact through the +x side of the plate on the same face.
  Index sideNode = 0;
  while (f.model.normals[sideNode].x < 0.5) ++sideNode;
  Contact side = f.contacts[0];
  side.toolNode = sideNode;
  side.normal = {1, 0, 0};
  f.contacts.push_back(side);
  f.patch.positions[1] = {0.195, 0.003, -0.1};  // inside, 5 mm from the +x side
  ResponseWorkspace workspace;
  std::vector<NodeCorrection> corrections;
  Wrench wrench;
  computeResponse(f.model, f.pose, f.patch, f.contacts, kSkin, kDt, {}, workspace, corrections, wrench);
  for (const NodeCorrection& c : corrections) {
    const Vec3 moved = f.patch.positions[c.vertex] + c.displacement;
    const bool outsideUnderside = moved.y <= -kSkin + 1e-12;
    const bool outsideSide = moved.x >= 0.2 + kSkin - 1e-12;
    EXPECT_TRUE(outsideUnderside || outsideSide) << "vertex " << c.vertex;
  }
}

}  // namespace
}  // namespace thintool
