// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "response/Separation.h"

#include "TestMeshes.h"
#include "geometry/Ccd.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace thintool {
namespace {

constexpr Real kClearance = SeparationSettings{}.clearance;

// A 0.4 × 0.02 × 0.4 plate centred at the origin (thin along y), or a 1 m × 2 mm × 2 mm needle
// along x.
ToolModel plate() { return buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), ToolModelSettings{}); }
ToolModel needle() { return buildToolModel(makeBoxMesh({0.5, 0.001, 0.001}), ToolModelSettings{}); }

Pose at(const Vec3& translation) {
  Pose pose;
  pose.translation = translation;
  return pose;
}

struct Patch {
  SeparationPatch patch;
  Index node(const Vec3& start, const Vec3& end, Real inverseMass = 1) {
    return patch.addVertex(patch.vertexCount(), start, end, inverseMass);
  }
};

TEST(Separation, NodeInsideLeavesThroughTheFaceItEnteredBy) {
  const ToolModel piece = plate();
  Patch p;
  // Came from above and was left 15 mm deep, past the mid-plane: the nearest face is the bottom.
  const Index v = p.node({0.05, 0.03, 0}, {0.05, -0.005, 0});
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 1u);
  EXPECT_EQ(counts.nodesInside, 0u);
  EXPECT_NEAR(p.patch.positions[v].y, 0.01 + kClearance, 1e-12);
  EXPECT_EQ(p.patch.positions[v].x, 0.05);
  EXPECT_EQ(p.patch.moved[v], 1);
}

TEST(Separation, NodeCarriedThroughGoesBackAndOneRoundTheRimStays) {
  const ToolModel piece = plate();
  Patch p;
  const Index through = p.node({0.1, 0.05, 0}, {0.1, -0.05, 0});
  const Index round = p.node({0.22, 0.05, 0}, {0.21, -0.05, 0});  // passes beside the +x rim
  // Cuts the +x rim's lower corner: in by the rim, out by the bottom; it goes back beside the rim.
  const Index corner = p.node({0.25, 0.05, 0}, {0.15, -0.05, 0});
  separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_NEAR(p.patch.positions[through].y, 0.01 + kClearance, 1e-12);
  EXPECT_EQ(p.patch.positions[round].y, -0.05);
  EXPECT_EQ(p.patch.moved[round], 0);
  EXPECT_NEAR(p.patch.positions[corner].x, 0.2 + kClearance, 1e-12);
  EXPECT_EQ(p.patch.positions[corner].y, -0.05);
}

TEST(Separation, ANodeEnclosedByTheSurfaceGoesBackFromAPathThroughARoundPiece) {
  // A ball of radius 1 (the hull of an icosphere of 320 faces), still. Both nodes pass under
  // its top, 0.1 deep, in by a face and out by one less than 60° from it: a node of the surface rode
  // round the top and stays; a node the surface encloses (a tetrahedral body's interior node)
  // cannot ride against the piece, went through it, and goes back in front of the face it entered
  // by, the clearance beyond it.
  const ToolModel ball = buildToolModel(test::icosphere(1, {0, 0, 0}, 2), ToolModelSettings{});
  const Vec3 start{-0.8, 0.9, 0};
  const Vec3 end{0.8, 0.9, 0};
  Patch p;
  const Index riding = p.node(start, end);
  const Index enclosed = p.node(start, end);
  p.patch.enclosed[enclosed] = 1;
  const SeparationCounts counts = separateFromPiece(ball, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesInside, 0u);
  EXPECT_EQ(p.patch.moved[riding], 0);
  EXPECT_EQ(p.patch.positions[riding], end);
  EXPECT_EQ(p.patch.moved[enclosed], 1);
  const ClipResult path = clipSegmentConvex(ball.planes, 0, start, end);
  ASSERT_TRUE(path.hit);
  EXPECT_NEAR(ball.planes[path.enterPlane].signedDistance(p.patch.positions[enclosed]), kClearance, 1e-12);
}

TEST(Separation, AnEnclosedNodeThatWouldLandInANearPieceGoesBackWhereItBegan) {
  // The same path through the ball, with a second piece of the tool where the node would land in
  // front of the face it entered by (a box and a ball side by side): it goes back where it was
  // beside the ball at the start, outside both.
  const ToolModel ball = buildToolModel(test::icosphere(1, {0, 0, 0}, 2), ToolModelSettings{});
  const Vec3 start{-0.8, 0.9, 0};
  const Vec3 end{0.8, 0.9, 0};
  const ClipResult path = clipSegmentConvex(ball.planes, 0, start, end);
  ASSERT_TRUE(path.hit);
  const Plane& entry = ball.planes[path.enterPlane];
  const Vec3 inFront = end + entry.normal * (kClearance - entry.signedDistance(end));
  const ToolModel box = buildToolModel(makeBoxMesh({0.05, 0.05, 0.05}), ToolModelSettings{});
  const std::vector<NearPiece> near = {NearPiece{&box, at(inFront)}};
  Patch p;
  const Index enclosed = p.node(start, end);
  p.patch.enclosed[enclosed] = 1;
  separateFromPiece(ball, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch, near);
  EXPECT_EQ(p.patch.moved[enclosed], 1);
  EXPECT_EQ(p.patch.positions[enclosed], start);
}

TEST(Separation, ATurnSweepsAlongItsArcNotItsChord) {
  const ToolModel piece = plate();
  // The plate turns a quarter turn about z in one step: its +x half sweeps up through y > 0.
  Pose end;
  end.rotation = rotationAboutAxis({0, 0, 1}, kPi / 2);
  const PieceMotion motion(Pose{}, end, SeparationSettings{}.maxTurnPerSample);
  EXPECT_NEAR(motion.turn(), kPi / 2, 1e-12);
  EXPECT_EQ(motion.samples(), 18);
  Patch p;
  // Above the plate at x = 0.1 and still there: the end pose does not hold it (it is beside the
  // turned plate), but the arc went through it, so it was carried; it goes to the plate's top
  // face, now facing -x.
  const Index swept = p.node({0.1, 0.02, 0}, {0.1, 0.02, 0});
  // Below the plate on the same side: the arc moved away from it.
  const Index spared = p.node({0.1, -0.02, 0}, {0.1, -0.02, 0});
  separateFromPiece(piece, motion, {}, p.patch);
  EXPECT_EQ(p.patch.moved[spared], 0);
  EXPECT_EQ(p.patch.moved[swept], 1);
  const Vec3 local = end.applyInverse(p.patch.positions[swept]);
  EXPECT_NEAR(local.y, 0.01 + kClearance, 1e-9);
  EXPECT_LT(p.patch.positions[swept].x, -0.01);
}

TEST(Separation, ANodeTheArcTakesPastTheMidPlaneAndBackOutIsCarriedThrough) {
  const ToolModel piece = plate();
  // 170° about z in one step. The node starts just under the plate and moves straight in the world.
  // On the arc it goes in by the bottom face, 18 mm up to 8 mm short of the top, and back out by
  // the bottom; on the chord it goes in by the bottom and out by the top. It ends beside the rims,
  // above the plate's mid-plane: both readings took it past the mid-plane inside the plate.
  Pose end;
  end.rotation = rotationAboutAxis({0, 0, 1}, kPi * 170 / 180);
  const PieceMotion motion(Pose{}, end, SeparationSettings{}.maxTurnPerSample);
  Patch p;
  const Index v = p.node({-0.13, -0.0101, 0.01}, {0.27, -0.11, -0.28});
  ASSERT_GT(end.applyInverse({0.27, -0.11, -0.28}).y, 0.05);
  separateFromPiece(piece, motion, {}, p.patch);
  EXPECT_EQ(p.patch.moved[v], 1);
  const Vec3 local = end.applyInverse(p.patch.positions[v]);
  EXPECT_NEAR(local.y, -0.01 - kClearance, 1e-9);
}

// A small upright face 0.35 m out from the plate's centre, at its level, that stays still while the
// plate turns 120° about y in one step (its corners sweep the disc of radius 0.283 m). In the
// plate's frame the face goes a third of the way round: on the chord no axis separates it on one
// side at both ends.
constexpr Vec3 kStillFace[3] = {{0.35, -0.1, -0.01}, {0.35, -0.1, 0.01}, {0.35, 0.1, 0}};
Pose thirdOfATurn() {
  Pose end;
  end.rotation = rotationAboutAxis({0, 1, 0}, 2 * kPi / 3);
  return end;
}
void addStillFace(Patch& p, Index (&v)[3]) {
  for (int k = 0; k < 3; ++k) v[k] = p.node(kStillFace[k], kStillFace[k]);
  p.patch.faces.push_back({v[0], v[1], v[2]});
}

TEST(Separation, AFaceBesideATurningPlateThatNeverReachedItStays) {
  const ToolModel piece = plate();
  const PieceMotion motion(Pose{}, thirdOfATurn(), SeparationSettings{}.maxTurnPerSample);
  Patch p;
  Index v[3];
  addStillFace(p, v);
  const SeparationCounts counts = separateFromPiece(piece, motion, {}, p.patch);
  EXPECT_EQ(counts.facesMoved, 0u);
  EXPECT_EQ(counts.arcSpared, 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(p.patch.positions[v[k]], kStillFace[k]) << "node " << k;
}

TEST(Separation, AlongTheChordAloneAFaceTheArcSparedGoesBackToItsSide) {
  const ToolModel piece = plate();
  // The face of the test above: the arc spares it, the chord takes it a third of the way round
  // the plate. Read along the chord alone, the stage puts it back on a side it had at the start,
  // seen from the plate, as the glue asks when the plate ended inside a closed body.
  const Pose end = thirdOfATurn();
  const PieceMotion motion = PieceMotion(Pose{}, end, SeparationSettings{}.maxTurnPerSample).alongChord();
  EXPECT_EQ(motion.samples(), 1);
  EXPECT_NEAR(motion.turn(), 2 * kPi / 3, 1e-12);
  Patch p;
  Index v[3];
  addStillFace(p, v);
  const SeparationCounts counts = separateFromPiece(piece, motion, {}, p.patch);
  EXPECT_GE(counts.facesMoved, 1u);
  EXPECT_EQ(counts.arcSpared, 0u);
  Vec3 local[3];
  for (int k = 0; k < 3; ++k) local[k] = end.applyInverse(p.patch.positions[v[k]]);
  EXPECT_FALSE(triangleMeetsPiece(piece, local[0], local[1], local[2], 0));
  // At the start the face lay beyond the plate's +x rim; left where it is, it would lie on the -x
  // side, seen from the turned plate. Read along the chord it goes back to the +x side.
  EXPECT_LT(end.applyInverse(kStillFace[0]).x, 0);
  EXPECT_GT((local[0].x + local[1].x + local[2].x) / 3, 0.15);
}

TEST(Separation, HalfTurnAxisIsRecovered) {
  Pose end;
  end.rotation = rotationAboutAxis(normalizedOrZero({1, 2, 3}), kPi);
  end.translation = {1, 2, 3};
  const PieceMotion motion(Pose{}, end, 0.1);
  EXPECT_NEAR(motion.turn(), kPi, 1e-9);
  const Pose atEnd = motion.at(1 - 1e-12);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(length(atEnd.rotation.row[i] - end.rotation.row[i]), 0, 1e-7);  // the axis of a half turn is good to √ε
  }
  const Pose half = motion.at(0.5);
  EXPECT_NEAR(length(half.translation - Vec3{0.5, 1, 1.5}), 0, 1e-12);
}

TEST(Separation, NeedleTipInAFaceInteriorMovesTheFacePastTheTip) {
  const ToolModel piece = needle();
  // A 0.4 m triangle in the plane x = 0.45 facing +x; the needle's tip (x = 0.5) came through it
  // from x < 0.45 while the face stood still: every node stays outside the needle.
  Patch p;
  const Vec3 corners[3] = {{0.45, -0.2, -0.2}, {0.45, 0.2, -0.2}, {0.45, 0, 0.3}};
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(corners[k], corners[k]);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  const Pose start = at({-0.1, 0, 0});  // the tip at x = 0.4, short of the face
  EXPECT_TRUE(triangleMeetsPiece(piece, corners[0], corners[1], corners[2], 0));
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(start, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.facesMoved, 1u);
  EXPECT_EQ(counts.facesPierced, 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(p.patch.positions[v[k]].x, 0.5 + kClearance, 1e-9);  // past the tip, along +x
  }
  EXPECT_FALSE(triangleMeetsPiece(piece, p.patch.positions[v[0]], p.patch.positions[v[1]], p.patch.positions[v[2]],
                                  0));
}

TEST(Separation, AFaceTheSolverCarriedOverTheNeedlesEndGoesBackBeyondIt) {
  const ToolModel piece = needle();
  // The needle stands still; the soft solver carried a face from 2 cm beyond its end (x = 0.5) to
  // 1 cm over it: the end's corners pierce the face, none of its nodes entered the needle.
  Patch p;
  const auto corner = [](Real x, int k) {
    const Vec3 offsets[3] = {{0, 0.03, 0}, {0, -0.03, 0.03}, {0, -0.03, -0.03}};
    return Vec3{x, 0, 0} + offsets[k];
  };
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(corner(0.52, k), corner(0.49, k));
  p.patch.faces.push_back({v[0], v[1], v[2]});
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_EQ(counts.nodesMoved, 0u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.patch.positions[v[k]].x, 0.5 + kClearance, 1e-9);
}

TEST(Separation, AThinToolThatWentThroughAFaceInOneStepTakesItAlong) {
  const ToolModel piece = needle();
  // The needle came down 5 cm through a large face between its nodes: at the end of the step the
  // face is wholly above it and meets it nowhere, but it was below at the start.
  Patch p;
  const Vec3 corners[3] = {{-0.3, 0, -0.3}, {0.3, 0, -0.3}, {0, 0, 0.3}};
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(corners[k], corners[k]);
  p.patch.faces.push_back({v[0], v[2], v[1]});
  separateFromPiece(piece, PieceMotion(at({0, 0.03, 0}), at({0, -0.02, 0}), 0.1), {}, p.patch);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.patch.positions[v[k]].y, -0.021 - kClearance, 1e-9);
}

TEST(Separation, FaceSideComesFromTheStartOfTheStep) {
  const ToolModel piece = plate();
  // A large face under the plate, which came down through it by 15 mm in one step: most of the
  // plate is now below the face, yet the plate was above it, so the face goes below the plate.
  Patch p;
  const Vec3 corners[3] = {{-1, 0.005, -1}, {1, 0.005, -1}, {0, 0.005, 1}};
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(corners[k], corners[k]);
  p.patch.faces.push_back({v[0], v[2], v[1]});
  separateFromPiece(piece, PieceMotion(at({0, 0.02, 0}), Pose{}, 0.1), {}, p.patch);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.patch.positions[v[k]].y, -0.01 - kClearance, 1e-9);
}

TEST(Separation, PinnedNodesNeverMoveAndWhatIsLeftIsCounted) {
  const ToolModel piece = plate();
  Patch p;
  const Index pinned = p.node({0, 0.03, 0}, {0, 0, 0}, 0);
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(p.patch.positions[pinned].y, 0);
  EXPECT_EQ(counts.nodesInside, 1u);
}

TEST(Separation, FacesOfMovableNodesShareAPinnedNeighboursMove) {
  const ToolModel piece = needle();
  Patch p;
  const Vec3 corners[3] = {{0.45, -0.2, -0.2}, {0.45, 0.2, -0.2}, {0.45, 0, 0.3}};
  const Index a = p.node(corners[0], corners[0], 0);
  const Index b = p.node(corners[1], corners[1]);
  const Index c = p.node(corners[2], corners[2]);
  p.patch.faces.push_back({a, b, c});
  separateFromPiece(piece, PieceMotion(at({-0.1, 0, 0}), Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(p.patch.positions[a].x, 0.45);
  EXPECT_GT(p.patch.positions[b].x, 0.5);
  EXPECT_FALSE(triangleMeetsPiece(piece, p.patch.positions[a], p.patch.positions[b], p.patch.positions[c], 0));
}

// A still face across the still plate, corner `pinned` pinned: where the stage leaves its corners,
// and what it left pierced.
struct StillFace {
  std::array<Vec3, 3> x;
  Index facesPierced = 0;
};
StillFace separateStillFace(const ToolModel& piece, const std::array<Vec3, 3>& corners, int pinned) {
  Patch p;
  for (int k = 0; k < 3; ++k) p.node(corners[k], corners[k], k == pinned ? 0 : 1);
  p.patch.faces.push_back({0, 1, 2});
  EXPECT_TRUE(triangleMeetsPiece(piece, corners[0], corners[1], corners[2], 0)) << "the face must start across it";
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  return {{p.patch.positions[0], p.patch.positions[1], p.patch.positions[2]}, counts.facesPierced};
}

TEST(Separation, AFaceHangingFromAPinnedNodeAcrossTheRimSwingsBeyondTheRim) {
  // A sheet's corner face: pinned above the plate and beyond its +z rim, one free node under the
  // plate, one beside its +x edge. The edge from the free node under the plate up to the pinned
  // one passes through the plate near the rim.
  const ToolModel piece = plate();
  const std::array<Vec3, 3> corners{{{0.15, -0.012, 0.17}, {0.25, 0.02, 0.17}, {0.15, 0.1, 0.25}}};
  const int under = 0, beside = 1, pinned = 2;
  const StillFace face = separateStillFace(piece, corners, pinned);
  const std::array<Vec3, 3>& x = face.x;
  EXPECT_EQ(face.facesPierced, 0u);
  EXPECT_FALSE(triangleMeetsPiece(piece, x[under], x[beside], x[pinned], 0));
  EXPECT_EQ(x[pinned], corners[2]);
  // Round the rim, not through the plate: the node under it stays under it.
  EXPECT_LT(x[under].y, -0.01);
  EXPECT_GE(x[under].z, 0.2);
}

TEST(Separation, AFaceWrappedRoundTheRimFromAPinnedNodeUnderThePlateSwingsAboutTheRim) {
  // Pinned under the plate inside its outline, one free node above the plate just inside the +z
  // rim, one beyond the rim: the edge up from the pinned node passes through the plate. No face
  // plane has the pinned node beyond it and a straight way out for the node above; a plane through
  // the rim, turned between the underside and the +z side, has both.
  const ToolModel piece = plate();
  const std::array<Vec3, 3> corners{{{0.1, -0.15, 0.18}, {0.05, 0.05, 0.199}, {0, 0, 0.22}}};
  const int pinned = 0, above = 1, beyond = 2;
  const StillFace face = separateStillFace(piece, corners, pinned);
  const std::array<Vec3, 3>& x = face.x;
  EXPECT_EQ(face.facesPierced, 0u);
  EXPECT_FALSE(triangleMeetsPiece(piece, x[pinned], x[above], x[beyond], 0));
  EXPECT_EQ(x[pinned], corners[0]);
  // Round the rim, not through the plate.
  EXPECT_GT(x[above].y, 0.01);
  EXPECT_GT(x[above].z, 0.2);
  EXPECT_LT(length(x[above] - corners[1]), 0.05) << "a swing about the rim, not a fling";
}

// A sheet's corner face that the plate slid in under, 0.3 m along x in one step: pinned high above
// the plate, its two free nodes below it, all three still. At the end the plate lies across the
// face, inside its outline at the +z rim, and the edges up to the pinned node pass through it. No
// plane the pinned node is beyond has a way out for the nodes below that keeps them outside the
// underside. The rounds bring it clear beside the plate; the last resort, which carries nothing
// tied to a pinned node, slides the nodes past the rim, as far as the plate went at most.
const std::array<Vec3, 3> kSlidUnder{{{0.05, 0.25, -0.15}, {0.08, -0.02, 0.19}, {0.15, -0.04, 0.17}}};
const PieceMotion kSlideAlongX(at({-0.3, 0, 0}), Pose{}, 0.1);

SeparationPatch slidUnderFace() {
  Patch p;
  for (int k = 0; k < 3; ++k) p.node(kSlidUnder[k], kSlidUnder[k], k == 0 ? 0 : 1);
  p.patch.faces.push_back({0, 1, 2});
  EXPECT_TRUE(triangleMeetsPiece(plate(), kSlidUnder[0], kSlidUnder[1], kSlidUnder[2], 0)) << "it must end across";
  return p.patch;
}

void expectSlidPastTheRim(const SeparationPatch& patch, const SeparationCounts& counts) {
  const std::vector<Vec3>& x = patch.positions;
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_FALSE(triangleMeetsPiece(plate(), x[0], x[1], x[2], 0));
  EXPECT_EQ(x[0], kSlidUnder[0]);
  for (int k : {1, 2}) {
    // Its path in the plate's frame passes under or beside the plate, never through it.
    const Vec3 from = kSlideAlongX.start().applyInverse(kSlidUnder[k]);
    const Vec3 to = kSlideAlongX.end().applyInverse(x[k]);
    EXPECT_FALSE(triangleMeetsPiece(plate(), from, to, to, 0)) << "node " << k;
    EXPECT_LT(to.y, 0.01) << "node " << k << " went over to the pinned node's side";
    EXPECT_LE(length(x[k] - kSlidUnder[k]), 0.6) << "node " << k;
  }
}

TEST(Separation, AFaceThePlateSlidUnderFromAPinnedNodeAboveComesClearWithoutGoingThroughIt) {
  SeparationPatch patch = slidUnderFace();
  SeparationSettings oneRound;
  oneRound.maxRounds = 1;
  const SeparationCounts counts = separateFromPiece(plate(), kSlideAlongX, oneRound, patch);
  expectSlidPastTheRim(patch, counts);
}

TEST(Separation, TheLastResortSlidesAFaceWithAPinnedNodePastTheRim) {
  SeparationPatch patch = slidUnderFace();
  const SeparationCounts counts = carryMeetingFaces(plate(), kSlideAlongX, {}, patch);
  EXPECT_EQ(counts.nodesMoved, 2u);
  expectSlidPastTheRim(patch, counts);
}

TEST(Separation, AStillPlateNeitherFlingsNorSlidesTheFreeNodesOfAFaceWithAPinnedNode) {
  // The same face with the plate and the nodes still: nothing in the step explains a move, and the
  // shares of a translation that would clear it are tens of centimetres. The face stays, counted.
  SeparationPatch patch = slidUnderFace();
  const SeparationCounts counts = separateFromPiece(plate(), PieceMotion(Pose{}, Pose{}, 0.1), {}, patch);
  EXPECT_EQ(counts.facesPierced, 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(patch.positions[k], kSlidUnder[k]) << "node " << k;
}

TEST(Separation, NoFaceSlidesPastTheRimOfAStillPiece) {
  // The same face with the plate still: nothing swept the nodes, and nothing may fling them.
  SeparationPatch patch = slidUnderFace();
  const SeparationCounts counts = carryMeetingFaces(plate(), PieceMotion(Pose{}, Pose{}, 0.1), {}, patch);
  EXPECT_EQ(counts.nodesMoved, 0u);
  EXPECT_EQ(counts.facesPierced, 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(patch.positions[k], kSlidUnder[k]) << "node " << k;
}

TEST(Separation, FacesThatWantASharedNodeOnOppositeSidesMoveTogether) {
  // Two faces in the needle's plane, one either side of it, sharing the node in the needle: each
  // clears by going its own way, taking the node along, and one round leaves one of them pierced.
  // Moved together when the rounds run out, both clear.
  const ToolModel piece = needle();
  Patch p;
  const Vec3 corners[5] = {{0, 0, 0}, {0.05, 0, 0.1}, {-0.05, 0, 0.1}, {0.05, 0, -0.1}, {-0.05, 0, -0.1}};
  Index v[5];
  for (int k = 0; k < 5; ++k) v[k] = p.node(corners[k], corners[k]);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  p.patch.faces.push_back({v[0], v[4], v[3]});
  SeparationSettings oneRound;
  oneRound.maxRounds = 1;
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), oneRound, p.patch);
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_EQ(counts.nodesInside, 0u);
  for (const std::array<Index, 3>& f : p.patch.faces) {
    EXPECT_FALSE(triangleMeetsPiece(piece, p.patch.positions[f[0]], p.patch.positions[f[1]], p.patch.positions[f[2]], 0));
  }
}

TEST(Separation, TwoFacesRoundANeedleOneWithAPinnedNodeComeClear) {
  // As above, with the outer node of one face pinned 5 cm above or below the needle: both faces
  // must end on the pinned node's side, the only one where that face comes clear too.
  for (const Real side : {Real(1), Real(-1)}) {
    const ToolModel piece = needle();
    Patch p;
    const Vec3 corners[5] = {{0, 0, 0}, {0.05, 0.05 * side, 0.1}, {-0.05, 0, 0.1}, {0.05, 0, -0.1}, {-0.05, 0, -0.1}};
    Index v[5];
    for (int k = 0; k < 5; ++k) v[k] = p.node(corners[k], corners[k], k == 1 ? 0 : 1);
    p.patch.faces.push_back({v[0], v[1], v[2]});
    p.patch.faces.push_back({v[0], v[4], v[3]});
    SeparationSettings oneRound;
    oneRound.maxRounds = 1;
    const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), oneRound, p.patch);
    EXPECT_EQ(counts.facesPierced, 0u) << "side " << side;
    EXPECT_EQ(p.patch.positions[v[1]], corners[1]);
    for (const std::array<Index, 3>& f : p.patch.faces) {
      EXPECT_FALSE(triangleMeetsPiece(piece, p.patch.positions[f[0]], p.patch.positions[f[1]], p.patch.positions[f[2]], 0))
          << "side " << side;
    }
  }
}

TEST(Separation, FacesMovedTogetherAreNotPushedIntoANearPiece) {
  // A small face inside the corner of a block, its nodes each nearest a different side: they leave
  // by three sides and the face still cuts the corner, so when the rounds run out it moves on
  // whole, about 0.1 m along one of the block's normals. A plate stands beside the block, where
  // the move the stage prefers would put the face. Told of the plate, the face goes another way;
  // not told, it goes into the plate. With the plate further off, telling changes nothing.
  const ToolModel block = buildToolModel(makeBoxMesh({0.1, 0.1, 0.1}), ToolModelSettings{});
  const ToolModel other = buildToolModel(makeBoxMesh({0.01, 0.2, 0.2}), ToolModelSettings{});
  const Vec3 corners[3] = {{0.09, 0, 0}, {0, 0.09, 0}, {0, 0, 0.09}};
  SeparationSettings oneRound;
  oneRound.maxRounds = 1;
  const auto run = [&](const Pose& plateEnd, bool told, bool& inPlate) {
    Patch p;
    for (const Vec3& corner : corners) p.node(corner, corner);
    p.patch.faces.push_back({0, 1, 2});
    std::vector<NearPiece> near;
    if (told) near.push_back({&other, plateEnd});
    const SeparationCounts counts = separateFromPiece(block, PieceMotion(Pose{}, Pose{}, 0.1), oneRound, p.patch, near);
    EXPECT_EQ(counts.facesPierced, 0u);
    EXPECT_EQ(counts.nodesInside, 0u);
    Vec3 local[3];
    for (int k = 0; k < 3; ++k) local[k] = plateEnd.applyInverse(p.patch.positions[static_cast<Index>(k)]);
    inPlate = triangleMeetsPiece(other, local[0], local[1], local[2], 0);
    return p.patch.positions;
  };
  bool inPlate = false;
  run(at({0.16, 0, 0}), false, inPlate);
  EXPECT_TRUE(inPlate);
  run(at({0.16, 0, 0}), true, inPlate);
  EXPECT_FALSE(inPlate);
  bool farInPlate = true;
  const std::vector<Vec3> notTold = run(at({0.25, 0, 0}), false, farInPlate);
  EXPECT_FALSE(farInPlate);
  EXPECT_EQ(run(at({0.25, 0, 0}), true, farInPlate), notTold);
}

TEST(Separation, SettingsAreValidated) {
  EXPECT_TRUE(validateSeparationSettings({}).empty());
  SeparationSettings bad;
  bad.clearance = 0;
  EXPECT_FALSE(validateSeparationSettings(bad).empty());
  bad = {};
  bad.maxRounds = 0;
  EXPECT_FALSE(validateSeparationSettings(bad).empty());
  bad = {};
  bad.maxTurnPerSample = std::nan("");
  EXPECT_FALSE(validateSeparationSettings(bad).empty());
}

// A face that fell from 3 cm above the still plate into it, as the solver left it.
struct FallenFace {
  const Vec3 start[3] = {{-0.05, 0.03, -0.05}, {0.05, 0.03, -0.05}, {0, 0.03, 0.05}};
  Patch p;
  Index v[3];
  FallenFace() {
    for (int k = 0; k < 3; ++k) v[k] = p.node(start[k], start[k] - Vec3{0, 0.03, 0});
    p.patch.faces.push_back({v[0], v[1], v[2]});
  }
};

TEST(Separation, NoFaceMoveTakesANodePastItsPlaceCarriedWithThePiece) {
  // The fallen face, which an earlier round (another face sharing its nodes) has already pushed
  // half a metre aside. Put back above the plate from there, its nodes would end half a metre from
  // where the solver left them; their places at the start are 3 cm away, and they go there.
  const ToolModel piece = plate();
  FallenFace face;
  for (Index vertex : face.v) face.p.patch.positions[vertex] += Vec3{0.5, 0, 0};
  separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, face.p.patch);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(length(face.p.patch.positions[face.v[k]] - face.start[k]), 0, 1e-12) << "node " << k;
    EXPECT_EQ(face.p.patch.moved[face.v[k]], 1);
  }
}

TEST(Separation, AFaceMoveSendsBackOnlyTheNodeThatWouldGoTooFar) {
  // The fallen face, of which an earlier round has pushed one node alone half a metre aside. That
  // node goes back to its place at the start; the others take their shares of the move, which put
  // them just above the plate, not back where they began: sent back with it, the nodes beside a
  // moving piece rode along with it, step after step.
  const ToolModel piece = plate();
  FallenFace face;
  const SeparationPatch& patch = face.p.patch;
  face.p.patch.positions[face.v[0]] += Vec3{0.5, 0, 0};
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, face.p.patch);
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_NEAR(length(patch.positions[face.v[0]] - face.start[0]), 0, 1e-12);
  for (int k = 1; k < 3; ++k) {
    const Vec3& at = patch.positions[face.v[k]];
    EXPECT_GT(at.y, 0.01) << "node " << k << " is in the plate";
    EXPECT_LT(at.y, 0.02) << "node " << k << " went back to its start";
    EXPECT_EQ(patch.moved[face.v[k]], 1);
  }
  EXPECT_FALSE(triangleMeetsPiece(piece, patch.positions[face.v[0]], patch.positions[face.v[1]],
                                  patch.positions[face.v[2]], 0));
}

// A face hanging over the still plate's rim from two heavy nodes far beyond it, its light node
// over the plate, which the solver took 7 mm down into the plate. Shares of the way back out would
// take the light node three times the face's move, 16.5 mm, further than twice anything the step
// did (the plate stood still, the node moved 7 mm); the light node goes back to its place at the
// start instead, beside the plate, and no node moves further than that.
TEST(Separation, NoFaceMoveTakesANodeFurtherThanTwiceWhatTheStepExplains) {
  const ToolModel piece = plate();
  Patch p;
  const Vec3 start[3] = {{0.15, 0.012, 0}, {0.65, 0, -0.1}, {0.65, 0, 0.1}};
  const Vec3 end[3] = {{0.15, 0.005, 0}, start[1], start[2]};
  const Real inverseMasses[3] = {1000, 1, 1};
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(start[k], end[k], inverseMasses[k]);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  EXPECT_TRUE(triangleMeetsPiece(piece, end[0], end[1], end[2], 0));
  const SeparationCounts counts = separateFromPiece(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.facesPierced, 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(length(p.patch.positions[v[k]] - end[k]), 2 * length(end[0] - start[0])) << "node " << k;
  }
  EXPECT_FALSE(triangleMeetsPiece(piece, p.patch.positions[v[0]], p.patch.positions[v[1]], p.patch.positions[v[2]],
                                  0));
}

TEST(Separation, TheLastResortCarriesTheFacesThatMeetThePieceWithIt) {
  // The plate comes down 10 cm onto a face 1 cm above it, which the solver leaves inside it, and a
  // second face shares two of its nodes, its third beside the plate and below it. Carried with the
  // plate, the first face ends 1 cm above it again; the second would then cross the plate's rim,
  // so its third node comes along too.
  const ToolModel piece = plate();
  Patch p;
  const Vec3 drop{0, -0.1, 0};
  const Vec3 start[4] = {{-0.05, 0.12, -0.05}, {0.1, 0.12, -0.05}, {0, 0.12, 0.05}, {0.3, 0.12, 0}};
  const Vec3 end[4] = {{-0.05, 0.005, -0.05}, {0.1, 0.005, -0.05}, {0, 0.005, 0.05}, {0.3, -0.05, 0}};
  Index v[4];
  for (int k = 0; k < 4; ++k) v[k] = p.node(start[k], end[k]);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  p.patch.faces.push_back({v[1], v[3], v[2]});
  const SeparationCounts counts = carryMeetingFaces(piece, PieceMotion(at({0, 0.1, 0}), Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 4u);
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_EQ(counts.nodesInside, 0u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(length(p.patch.positions[v[k]] - (start[k] + drop)), 0, 1e-12) << "node " << k;
    EXPECT_EQ(p.patch.moved[v[k]], 1);
  }
}

TEST(Separation, AFaceCrossedOnTheArcIsCarriedBackToItsPlaceBesideThePiece) {
  // The plate turns a quarter turn about z: its +x half sweeps up through a small face lying still
  // 2 cm above it, which ends beside the turned plate, clear of it. A second face, under the -x
  // half, which turns away from it, is never reached. Carried with the plate, the crossed face's
  // nodes go where they stood in its frame at the start: 2 cm above its top face, now facing -x.
  const ToolModel piece = plate();
  Pose end;
  end.rotation = rotationAboutAxis({0, 0, 1}, kPi / 2);
  const PieceMotion motion(Pose{}, end, SeparationSettings{}.maxTurnPerSample);
  Patch p;
  const Vec3 crossed[3] = {{0.1, 0.02, -0.02}, {0.12, 0.02, 0.02}, {0.08, 0.02, 0.02}};
  const Vec3 spared[3] = {{-0.1, 0.02, -0.02}, {-0.12, 0.02, 0.02}, {-0.08, 0.02, 0.02}};
  Index c[3];
  Index s[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = p.node(crossed[k], crossed[k]);
    s[k] = p.node(spared[k], spared[k]);
  }
  p.patch.faces.push_back({c[0], c[1], c[2]});
  p.patch.faces.push_back({s[0], s[1], s[2]});
  const SeparationCounts counts = carryCrossedFaces(piece, motion, {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 3u);
  EXPECT_EQ(counts.facesPierced, 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(length(p.patch.positions[c[k]] - end.apply(crossed[k])), 0, 1e-12) << "node " << k;
    EXPECT_LT(p.patch.positions[c[k]].x, -0.01) << "node " << k;
    EXPECT_EQ(p.patch.moved[c[k]], 1);
    EXPECT_EQ(p.patch.positions[s[k]], spared[k]) << "node " << k;
    EXPECT_EQ(p.patch.moved[s[k]], 0);
  }
}

TEST(Separation, TheLastResortMovesNothingWhereAPinnedNodeKeepsTheFaceInThePiece) {
  // The same fall with one node of the face pinned where the plate now is: no place of the other
  // two clears the face, and they stay where the solver left them; the face is counted.
  const ToolModel piece = plate();
  Patch p;
  const Vec3 start[3] = {{-0.05, 0.12, -0.05}, {0.1, 0.12, -0.05}, {0, 0.005, 0.05}};
  const Vec3 end[3] = {{-0.05, 0.005, -0.05}, {0.1, 0.005, -0.05}, {0, 0.005, 0.05}};
  Index v[3];
  for (int k = 0; k < 3; ++k) v[k] = p.node(start[k], end[k], k == 2 ? 0 : 1);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  const SeparationCounts counts = carryMeetingFaces(piece, PieceMotion(at({0, 0.1, 0}), Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 0u);
  EXPECT_EQ(counts.facesPierced, 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(p.patch.positions[v[k]], end[k]) << "node " << k;
}

TEST(Separation, TheLastResortSlidesAGroupThatTouchesAFaceWithAPinnedNodeRatherThanCarryIt) {
  // The fall of the first test, with a third face joining two of the face's nodes to a node pinned
  // beside the plate: that face cannot come along with the plate. The three free nodes slide clear
  // together instead, back out of the top they came in by, by less than carrying them would.
  const ToolModel piece = plate();
  Patch p;
  const Vec3 start[4] = {{-0.05, 0.12, -0.05}, {0.1, 0.12, -0.05}, {0, 0.12, 0.05}, {0.5, 0.12, 0}};
  const Vec3 end[4] = {{-0.05, 0.005, -0.05}, {0.1, 0.005, -0.05}, {0, 0.005, 0.05}, {0.5, 0.12, 0}};
  Index v[4];
  for (int k = 0; k < 4; ++k) v[k] = p.node(start[k], end[k], k == 3 ? 0 : 1);
  p.patch.faces.push_back({v[0], v[1], v[2]});
  p.patch.faces.push_back({v[1], v[3], v[2]});
  const SeparationCounts counts = carryMeetingFaces(piece, PieceMotion(at({0, 0.1, 0}), Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 3u);
  EXPECT_EQ(counts.facesPierced, 0u);
  EXPECT_EQ(p.patch.positions[v[3]], end[3]);
  const Vec3 slide = p.patch.positions[v[0]] - end[0];
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(length(p.patch.positions[v[k]] - end[k] - slide), 0, 1e-12) << "node " << k;
    EXPECT_GT(p.patch.positions[v[k]].y, 0.01) << "node " << k;
    EXPECT_LT(p.patch.positions[v[k]].y, 0.02) << "node " << k << " went as far as its carried place";
  }
}

TEST(Separation, TheNodesLastSayPutsANodeLeftInsideBackOutAndCountsTheFaceItLeavesPierced) {
  // Another piece's last move left a node 4 mm inside this plate, which it had entered from below;
  // the face it shares with two nodes pinned above the plate cannot come clear. The node goes back
  // out of the bottom, moved by nothing else, and the face is counted.
  const ToolModel piece = plate();
  Patch p;
  const Index inside = p.node({0.05, -0.03, 0}, {0.05, -0.006, 0});
  const Index pinnedA = p.node({0, 0.05, -0.05}, {0, 0.05, -0.05}, 0);
  const Index pinnedB = p.node({0.1, 0.05, 0.05}, {0.1, 0.05, 0.05}, 0);
  const Index outside = p.node({0.3, -0.03, 0}, {0.3, -0.02, 0});
  p.patch.faces.push_back({inside, pinnedA, pinnedB});
  const SeparationCounts counts = keepNodesOutside(piece, PieceMotion(Pose{}, Pose{}, 0.1), {}, p.patch);
  EXPECT_EQ(counts.nodesMoved, 1u);
  EXPECT_EQ(counts.nodesInside, 0u);
  EXPECT_EQ(counts.facesPierced, 1u);
  EXPECT_NEAR(p.patch.positions[inside].y, -0.01 - kClearance, 1e-12);
  EXPECT_EQ(p.patch.positions[inside].x, 0.05);
  EXPECT_EQ(p.patch.moved[inside], 1);
  for (const Index still : {pinnedA, pinnedB, outside}) EXPECT_EQ(p.patch.moved[still], 0) << "node " << still;
}

}  // namespace
}  // namespace thintool
