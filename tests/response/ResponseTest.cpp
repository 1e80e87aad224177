// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "response/Response.h"

#include <gtest/gtest.h>

#include <limits>

namespace thintool {
namespace {

constexpr Real kSkin = 0.001;
constexpr Real kDt = 0.01;
// Every point keeps the whole skin, wherever it began the step (ToolOptions::skinGrowthSpeed).
constexpr Real kSkinGrowthSpeed = std::numeric_limits<Real>::infinity();

// A 0.4 × 0.02 × 0.4 plate whose underside is at y = 0, and a soft patch made of given triangles.
struct Fixture {
  ToolModel model;
  Pose pose;
  SoftPatch patch;
  std::vector<PatchContact> contacts;
  ResponseResult result;
  std::vector<NodeCorrection>& corrections = result.corrections;
  Wrench& wrench = result.wrench;
  Real skinGrowthSpeed = kSkinGrowthSpeed;

  Fixture() {
    ToolModelSettings settings;
    settings.sampling.spacing = 0.4;
    model = buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), settings);
    pose.translation = {0, 0.01, 0};
  }
  Index vertex(const Vec3& p, Real inverseMass = 2, const Vec3* previous = nullptr) {
    patch.positions.push_back(p);
    patch.previousPositions.push_back(previous != nullptr ? *previous : p);
    patch.inverseMasses.push_back(inverseMass);
    patch.nodeIds.push_back(patch.vertexCount() - 1);
    return patch.vertexCount() - 1;
  }
  // A triangle 3 mm inside the underside, counter-clockwise seen from below; returns the face.
  Index triangleInside(Real inverseMassOfThird = 2) {
    const Index a = vertex({-0.1, 0.003, -0.1});
    const Index b = vertex({0.1, 0.003, -0.1});
    const Index c = vertex({0, 0.003, 0.1}, inverseMassOfThird);
    return face(a, c, b);
  }
  Index face(Index a, Index b, Index c) {
    patch.faces.push_back({a, b, c});
    patch.faceIds.push_back(patch.faceCount() - 1);
    return patch.faceCount() - 1;
  }
  Index nodeFacing(const Vec3& normal) const {
    Index node = 0;
    while (dot(model.normals[node], normal) < 0.5) ++node;
    return node;
  }
  void contact(Index faceIndex, const Vec3& normal, const Vec3& barycentric, Real depth) {
    PatchContact c;
    c.toolNode = nodeFacing(normal);
    c.patchFace = faceIndex;
    c.softNodeCount = 3;
    c.patchVertices = patch.faces[faceIndex];
    c.barycentric = barycentric;
    c.depth = depth;
    c.normal = normal;
    // The plane of the node's tool face, moved out by the skin, as detection sets it.
    c.offset = -dot(normal, pose.apply(model.positions[c.toolNode]) + normal * kSkin);
    contacts.push_back(c);
  }
  // A contact of a tool point with a face's centroid: the face must end in front of the plane
  // dot(normal, x) + offset = 0.
  void toolPoint(Index faceIndex, const Vec3& normal, Real offset) {
    PatchContact c;
    c.kind = ContactKind::ToolPoint;
    c.softNodeCount = 3;
    c.patchVertices = patch.faces[faceIndex];
    c.patchFace = faceIndex;
    c.barycentric = {Real(1) / 3, Real(1) / 3, Real(1) / 3};
    c.normal = normal;
    c.offset = offset;
    contacts.push_back(c);
  }
  // A swept contact of soft node v with the plate's underside, y = 0, grown by the skin.
  PatchContact& underside(Index v) {
    PatchContact c;
    c.kind = ContactKind::SoftNode;
    c.softNodeCount = 1;
    c.patchVertices = {v, kInvalidIndex, kInvalidIndex};
    c.barycentric = {1, 0, 0};
    c.normal = {0, -1, 0};
    c.offset = -kSkin;
    contacts.push_back(c);
    return contacts.back();
  }
  StepContext context(const Pose& previous) const { return {model, previous, pose, kDt, kSkin, skinGrowthSpeed}; }
  // The response's geometry alone unless a test asks for friction (on by default).
  static ResponseSettings frictionless() {
    ResponseSettings settings;
    settings.friction.enabled = false;
    return settings;
  }
  void respond(const ResponseSettings& settings = frictionless(), const Pose* previous = nullptr) {
    computeResponse(context(previous != nullptr ? *previous : pose), patch, contacts, settings, result);
  }
  Vec3 finalPosition(Index v) const {
    for (const NodeCorrection& c : corrections) {
      if (c.vertex == v) return patch.positions[v] + c.displacement;
    }
    return patch.positions[v];
  }
};

TEST(Response, NodesInsideTheToolLeaveThroughTheEntrySideAndPinnedNodesStay) {
  Fixture f;
  const Index a = f.vertex({-0.1, 0.003, -0.1});
  const Index b = f.vertex({0.1, 0.003, -0.1});
  const Index pinned = f.vertex({0, 0.003, 0.1}, 0);
  f.contact(f.face(a, pinned, b), {0, -1, 0}, {0.25, 0.5, 0.25}, 0.003);
  f.respond();
  EXPECT_EQ(f.finalPosition(pinned).y, 0.003);
  EXPECT_LE(f.finalPosition(a).y, -kSkin + 1e-12);
  EXPECT_LE(f.finalPosition(b).y, -kSkin + 1e-12);
  Vec3 expectedForce;
  for (const NodeCorrection& c : f.corrections) {
    EXPECT_NEAR(c.normal.y, -1, 1e-12);
    expectedForce -= c.displacement / (f.patch.inverseMasses[c.vertex] * kDt * kDt);
  }
  EXPECT_NEAR(f.wrench.force.y, expectedForce.y, 1e-9);
  EXPECT_GT(f.wrench.force.y, 0) << "the tissue pushes the tool up";
}

TEST(Response, BesideAPinnedNodeNoNodeMovesFurtherThanItsContactPoint) {
  // Weight 0.99 on a pinned node: the free node would need a hundred times the hit point's depth.
  // Leaving through its entry plane takes it out of the tool, then each of the four sweeps that
  // project the contact points moves it at most the point's depth; the point stays partly inside,
  // for the last word.
  Fixture f;
  const Index free = f.vertex({-0.1, 0.003, -0.1});
  const Index pin = f.vertex({0.1, 0.003, -0.1}, 0);
  const Index pin2 = f.vertex({0, 0.003, 0.1}, 0);
  f.contact(f.face(free, pin, pin2), {0, -1, 0}, {0.01, 0.99, 0}, 0.003);
  f.respond();
  const Real depth = 0.003 + kSkin;
  const Real moved = 0.003 - f.finalPosition(free).y;
  EXPECT_GT(moved, depth);
  EXPECT_LE(moved, 5 * depth + 1e-12);
  EXPECT_EQ(f.finalPosition(pin).y, 0.003);
  const Vec3 hit = f.finalPosition(free) * 0.01 + f.finalPosition(pin) * 0.99;
  EXPECT_GT(hit.y, -kSkin);
}

TEST(Response, BesideAPinnedNodeAFreeNodeStopsOnTheContactPlaneHoweverManyContactsPushIt) {
  // Three contact points next to two pinned nodes inside the plate: nothing can move them out. The
  // free node, half a skin under the plate, goes out to the skin's plane and no further: each
  // contact and each sweep would otherwise push it again by the points' depth.
  Fixture f;
  const Index free = f.vertex({-0.1, -0.0005, -0.1});
  const Index pin = f.vertex({0.1, 0.003, -0.1}, 0);
  const Index pin2 = f.vertex({0, 0.003, 0.1}, 0);
  const Index face = f.face(free, pin, pin2);
  f.contact(face, {0, -1, 0}, {0.01, 0.99, 0}, 0.003);
  f.contact(face, {0, -1, 0}, {0.01, 0, 0.99}, 0.003);
  f.contact(face, {0, -1, 0}, {0.02, 0.49, 0.49}, 0.003);
  f.respond();
  EXPECT_NEAR(f.finalPosition(free).y, -kSkin, 1e-12);
  EXPECT_EQ(f.finalPosition(pin).y, 0.003);
  EXPECT_EQ(f.finalPosition(pin2).y, 0.003);
}

TEST(Response, NoCorrectionEndsInsideTheTool) {
  // A face under the plate whose contact asks it up to y = 0.01, the plate's mid-plane: met by
  // moving its nodes, that would leave them inside the plate. They leave through the underside,
  // the face they were outside of at the start of the step.
  Fixture f;
  const Index a = f.vertex({-0.1, -0.005, -0.1});
  const Index b = f.vertex({0.1, -0.005, -0.1});
  const Index c = f.vertex({0, -0.005, 0.1});
  f.toolPoint(f.face(a, c, b), {0, 1, 0}, -0.01);
  f.respond();
  for (Index v : {a, b, c}) {
    EXPECT_NEAR(f.finalPosition(v).y, -kSkin, 1e-12) << "vertex " << v;
  }
}

// One soft node 3 mm inside the underside while the plate slides 2 mm along +x in the step: the
// normal move is 3 mm plus the skin, so friction can carry the node up to μ × 4 mm along.
Real frictionDrag(bool enabled, Real staticCoefficient, Real kineticCoefficient) {
  Fixture f;
  const Index v = f.vertex({0, 0.003, 0});
  f.underside(v).depth = 0.003;
  Pose previous = f.pose;
  previous.translation.x -= 0.002;
  ResponseSettings settings;
  settings.friction.enabled = enabled;
  settings.friction.staticCoefficient = staticCoefficient;
  settings.friction.kineticCoefficient = kineticCoefficient;
  f.respond(settings, &previous);
  EXPECT_NEAR(f.finalPosition(v).y, -kSkin, 1e-12) << "friction leaves the normal move alone";
  return f.finalPosition(v).x;
}

// A node that enters the plate's underside from start (y < 0) and is now at y = 0.002.
Index enteringNode(Fixture& f, Real startY) {
  const Vec3 start{0, startY, 0};
  const Index v = f.vertex({0, 0.002, 0}, 2, &start);
  f.underside(v);
  return v;
}

TEST(Response, ANodeThatBeganInsideTheSkinIsPushedOutNoFasterThanTheGrowthSpeed) {
  // It keeps where it began plus skinGrowthSpeed·dt of the skin, not all of it: pushed to the
  // full skin it would leave the step at skin/dt, a kick the tool's motion does not explain.
  Fixture f;
  f.skinGrowthSpeed = 0.01;  // 0.1 mm in the step
  const Index began = enteringNode(f, -0.0005);
  const Index beyond = enteringNode(f, -0.005);
  f.respond();
  EXPECT_NEAR(f.finalPosition(began).y, -0.0006, 1e-12);
  EXPECT_NEAR(f.finalPosition(beyond).y, -kSkin, 1e-12) << "a node from beyond the skin keeps all of it";

  Fixture atOnce;  // an infinite growth speed keeps the whole skin for every node
  const Index same = enteringNode(atOnce, -0.0005);
  atOnce.respond();
  EXPECT_NEAR(atOnce.finalPosition(same).y, -kSkin, 1e-12);
}

TEST(Response, AFaceContactKeepsTheWholeSkinWhereverItsNodesBegan) {
  // The point where a tool meets a face moves over the face from step to step; it has no place
  // at the start of the step to grow the skin from.
  Fixture f;
  f.skinGrowthSpeed = 0.01;
  const Vec3 start{0, -0.0005, 0};
  const Index a = f.vertex({-0.1, 0.003, -0.1}, 2, &start);
  const Index b = f.vertex({0.1, 0.003, -0.1}, 2, &start);
  const Index c = f.vertex({0, 0.003, 0.1}, 2, &start);
  f.contact(f.face(a, c, b), {0, -1, 0}, {Real(1) / 3, Real(1) / 3, Real(1) / 3}, 0.003);
  f.respond();
  const Vec3 hit = (f.finalPosition(a) + f.finalPosition(b) + f.finalPosition(c)) / 3;
  EXPECT_LE(hit.y, -kSkin + 1e-12);
}

TEST(Response, FrictionSticksWithinTheStaticConeAndSlidesBeyondIt) {
  EXPECT_EQ(frictionDrag(false, 0.8, 0.6), 0) << "off: frictionless";
  EXPECT_NEAR(frictionDrag(true, 0.8, 0.6), 0.002, 1e-12) << "2 mm slip < 0.8 × 4 mm: sticks";
  EXPECT_NEAR(frictionDrag(true, 0.3, 0.2), 0.2 * 0.004, 1e-12) << "2 mm > 0.3 × 4 mm: slides, μk × 4 mm";
}

TEST(Response, ANodeFrictionHoldsToAStillToolMovesOnlyAcrossTheToolsFace) {
  // The plate's rim (x = 0.2) pressed into a tilted face: the contact pushes the face along the
  // face's own normal, which leans 27° from the underside's. A node that sticks does not slide
  // along the tool's surface: it keeps only the part of its move across the underside. Kept along
  // the face's normal instead, a held tool's pushes walked nodes sideways step after step.
  Fixture f;
  const Vec3 normal = normalizedOrZero({0.5, -1, 0});
  const Vec3 rim{0.2, 0, 0};
  const Vec3 along = normalizedOrZero({1, 0.5, 0});  // in the face, across the rim
  const Index a = f.vertex(rim - along * 0.05 + Vec3{0, 0, -0.05} + normal * -0.002);
  const Index b = f.vertex(rim - along * 0.05 + Vec3{0, 0, 0.05} + normal * -0.002);
  const Index c = f.vertex(rim + along * 0.1 + normal * -0.002);
  f.toolPoint(f.face(a, b, c), normal, -(dot(normal, rim) + kSkin));
  ResponseSettings settings;
  settings.friction.enabled = true;
  f.respond(settings);
  for (Index v : {a, b, c}) {
    const Vec3 move = f.finalPosition(v) - f.patch.positions[v];
    EXPECT_LT(move.y, -1e-4) << "vertex " << v;
    EXPECT_NEAR(move.x, 0, 1e-12) << "vertex " << v;
    EXPECT_NEAR(move.z, 0, 1e-12) << "vertex " << v;
  }
}

TEST(Response, NodesAlreadyOutsideStayPut) {
  Fixture f;
  const Index a = f.vertex({-0.1, -0.002, -0.1});
  const Index b = f.vertex({0.1, -0.002, -0.1});
  const Index c = f.vertex({0, -0.002, 0.1});
  f.contact(f.face(a, c, b), {0, -1, 0}, {0.3, 0.3, 0.4}, -0.002);
  f.respond();
  EXPECT_TRUE(f.corrections.empty());
  EXPECT_EQ(f.wrench.force.y, 0);
}

TEST(Response, ANeedleInTheMiddleOfALargeFaceMovesTheFaceNotJustItsCorners) {
  // The corners are far outside the plate's footprint; only the hit point is inside.
  Fixture f;
  const Index a = f.vertex({-2, 0.003, -2});
  const Index b = f.vertex({2, 0.003, -2});
  const Index c = f.vertex({0, 0.003, 2});
  f.contact(f.face(a, c, b), {0, -1, 0}, {0.25, 0.5, 0.25}, 0.003);
  f.respond();
  const Vec3 hit = f.finalPosition(a) * 0.25 + f.finalPosition(c) * 0.5 + f.finalPosition(b) * 0.25;
  EXPECT_NEAR(hit.y, -kSkin, 1e-9);
  // The corner with the largest weight moves most.
  EXPECT_LT(f.finalPosition(c).y, f.finalPosition(a).y);
}

TEST(Response, ARimNodeEndsOutsideBothFacesThatHitIt) {
  Fixture f;
  const Index a = f.vertex({-0.1, 0.003, -0.1});
  const Index b = f.vertex({0.195, 0.003, -0.1});  // 5 mm inside the +x side
  const Index c = f.vertex({0, 0.003, 0.1});
  const Index face = f.face(a, c, b);
  f.contact(face, {0, -1, 0}, {0.3, 0.3, 0.4}, 0.003);
  f.contact(face, {1, 0, 0}, {0.1, 0.1, 0.8}, 0.005);
  f.respond();
  for (Index v : {a, b, c}) {
    const Vec3 p = f.finalPosition(v);
    EXPECT_TRUE(p.y <= -kSkin + 1e-12 || p.x >= 0.2 + kSkin - 1e-12) << "vertex " << v;
  }
}

TEST(Response, TheNodeGuardSendsASlippedNodeBackToTheSideItCameFrom) {
  // A node 15 mm up inside a 20 mm plate, nearer the top face, which no ray reported: it came
  // from below, so it must go out below.
  Fixture f;
  const Vec3 before{0, -0.03, 0};
  const Index slipped = f.vertex({0, 0.015, 0}, 2, &before);
  f.respond();
  ASSERT_EQ(f.corrections.size(), 1u);
  EXPECT_NEAR(f.finalPosition(slipped).y, -kSkin, 1e-12);

  Fixture unguarded;
  unguarded.vertex({0, 0.015, 0}, 2, &before);
  ResponseSettings settings;
  settings.guardNodes = false;
  unguarded.respond(settings);
  EXPECT_TRUE(unguarded.corrections.empty());
}

// A face beside the plate's +x rim, its two outer corners pinned, whose contact at the free corner
// pushes it in and up along a normal tilted over the plate, to target. Returns where the free corner
// ends, given where it was at the start of the step and where it is now.
Vec3 pushedOverTheRim(const Vec3& startOfStep, const Vec3& now, const Vec3& target) {
  Fixture f;
  const Index a = f.vertex({0.3, 0.03, -0.1}, 0);
  const Index free = f.vertex(now, 2, &startOfStep);
  const Index c = f.vertex({0.3, 0.03, 0.1}, 0);
  const Index face = f.face(a, free, c);
  PatchContact contact;
  contact.kind = ContactKind::ToolPoint;
  contact.patchFace = face;
  contact.softNodeCount = 3;
  contact.patchVertices = f.patch.faces[face];
  contact.barycentric = {0, 1, 0};
  contact.normal = normalizedOrZero(target - now);
  // The plane through target: the contact at the free corner moves it there.
  contact.offset = -dot(contact.normal, target);
  f.contacts.push_back(contact);
  f.respond();
  return f.finalPosition(free);
}

TEST(Response, ANodeAFaceContactWouldCarryAcrossThePlateGoesBackToTheFaceItCameBy) {
  // Below the plate and beside it at the start of the step, beside it and just above its top now:
  // pushed to 15 cm in from the rim and 11 cm above the top, its path from the start runs through
  // the plate. It goes back under the underside, the skin away.
  const Vec3 across = pushedOverTheRim({0.25, -0.05, 0}, {0.25, 0.03, 0}, {0.05, 0.13, 0});
  EXPECT_NEAR(across.y, -kSkin, 1e-12);
  EXPECT_NEAR(across.x, 0.05, 1e-12);

  // Pushed in less, to 5 cm in from the rim, its path passes round the rim, clear of the tool and
  // its skin: it stays where the contact put it.
  const Vec3 round = pushedOverTheRim({0.25, -0.05, 0}, {0.25, 0.03, 0}, {0.15, 0.13, 0});
  EXPECT_NEAR(round.x, 0.15, 1e-12);
  EXPECT_NEAR(round.y, 0.13, 1e-12);
}

TEST(Response, AHoldKeepsANodeOnTheSideItCameFrom) {
  // A node the plate passed beside its +x rim: below the plate at the start of the step, now above
  // it and still beside. It is farther in front of the top face than of the +x face, but held
  // behind the top face's plane the solver could pull it over the plate; it is held beside.
  Fixture f;
  const Vec3 start{0.25, -0.05, 0};
  f.vertex({0.25, 0.3, 0}, 2, &start);
  std::vector<NodeHold> holds;
  computeHolds(f.context(f.pose), f.patch, true, f.result, holds);
  ASSERT_EQ(holds.size(), 1u);
  EXPECT_NEAR(holds[0].normal.x, 1, 1e-12);
  EXPECT_NEAR(holds[0].offset, -(0.2 + kSkin), 1e-12);

  // One that started above the plate keeps the top face, which it is farthest in front of.
  Fixture above;
  const Vec3 startAbove{0.25, 0.1, 0};
  above.vertex({0.25, 0.3, 0}, 2, &startAbove);
  computeHolds(above.context(above.pose), above.patch, true, above.result, holds);
  ASSERT_EQ(holds.size(), 1u);
  EXPECT_NEAR(holds[0].normal.y, 1, 1e-12);
}

TEST(Response, PaperForceIsKTimesDepthSpreadByBarycentricWeights) {
  Fixture f;
  f.contact(f.triangleInside(0), {0, -1, 0}, {0.25, 0.5, 0.25}, 0.003);  // the weight 0.5 is pinned
  ResponseSettings settings;
  settings.kind = ResponseKind::PaperForce;
  settings.stiffness = 200;
  f.respond(settings);
  const Real force = 200 * (0.003 + kSkin);  // f = k·t, t measured into the skin
  ASSERT_EQ(f.corrections.size(), 2u);
  for (const NodeCorrection& c : f.corrections) {
    EXPECT_NEAR(c.displacement.y, -force * 0.25 * f.patch.inverseMasses[c.vertex] * kDt * kDt, 1e-15);
  }
  EXPECT_NEAR(f.wrench.force.y, force * 0.5, 1e-9) << "the pinned node's share goes nowhere";
}

TEST(Response, ACorrectionLongerThanTheStepCanJustifyIsDroppedWithItsReaction) {
  // Two nodes just under the plate, each with a faulty contact plane 3 m below it. Across the plate
  // and its skin is about 1.1 m, and the plate did not move: a 3 m move is justified only for the
  // node that the last sweep left 3.5 m away, which came that far this step. The other one's
  // correction is dropped, and with it its share of the reaction and of the next sweep's memory.
  Fixture f;
  const Index still = f.vertex({0, -0.0005, 0});
  const Index travelled = f.vertex({0.05, -0.0005, 0});
  f.patch.checkedPositions = {f.patch.positions[still], f.patch.positions[travelled] + Vec3{0, 3.5, 0}};
  f.underside(still).offset = -3;
  f.underside(travelled).offset = -3;
  f.respond();
  ASSERT_EQ(f.corrections.size(), 1u);
  EXPECT_EQ(f.result.rejected, 1u);
  EXPECT_EQ(f.corrections[0].vertex, travelled);
  EXPECT_NEAR(f.finalPosition(travelled).y, -3, 0.01);
  EXPECT_EQ(f.finalPosition(still).y, -0.0005);
  const Vec3 kept = f.corrections[0].displacement / (f.patch.inverseMasses[travelled] * kDt * kDt);
  EXPECT_NEAR(f.wrench.force.y, -kept.y, 1e-6) << "only the kept correction pushes the tool";
}

TEST(Response, NoneMovesNothing) {
  Fixture f;
  f.contact(f.triangleInside(), {0, -1, 0}, {0.3, 0.3, 0.4}, 0.003);
  ResponseSettings settings;
  settings.kind = ResponseKind::None;
  f.respond(settings);
  EXPECT_TRUE(f.corrections.empty());
}

}  // namespace
}  // namespace thintool
