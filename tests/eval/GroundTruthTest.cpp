// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The evaluation suite's ground truth: exact distances to convex pieces, the winding number,
// crossings counted only for nodes that pass through a piece (along a turning piece's arc), and
// faces that pierce a piece.

#include <GroundTruth.h>

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>

namespace thintool::eval {
namespace {

const Vec3 kPlateHalf{0.4, 0.01, 0.4};

TEST(GroundTruth, BoxSignedDistanceIsExactInsideAndOutside) {
  const SolidDistance plate(ConvexSolid::box(kPlateHalf));
  EXPECT_EQ(plate.thinAxis(), 1);
  EXPECT_NEAR(plate.signedDistance({0, 0, 0}), -0.01, 1e-15);
  EXPECT_NEAR(plate.signedDistance({0.395, 0.002, 0}), -0.005, 1e-15);  // nearer the rim than the faces
  EXPECT_NEAR(plate.signedDistance({0, 0.31, 0}), 0.3, 1e-15);
  // Beyond a corner the nearest point is the corner itself, not a face plane.
  EXPECT_NEAR(plate.signedDistance({0.7, 0.41, 0.4}), std::sqrt(0.3 * 0.3 + 0.4 * 0.4), 1e-12);
}

TEST(GroundTruth, TriangleDistanceHandlesEveryRegionAndDegenerateTriangles) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_NEAR(distanceSquaredToTriangle({0.2, 0.2, 0.5}, a, b, c), 0.25, 1e-15);   // above the face
  EXPECT_NEAR(distanceSquaredToTriangle({0.5, -1, 0}, a, b, c), 1, 1e-15);         // beside an edge
  EXPECT_NEAR(distanceSquaredToTriangle({-1, -1, 0}, a, b, c), 2, 1e-15);          // beyond a vertex
  // Collinear corners: the distance to the segment they span.
  EXPECT_NEAR(distanceSquaredToTriangle({0.5, 1, 0}, a, b, {2, 0, 0}), 1, 1e-15);
  EXPECT_NEAR(distanceSquaredToTriangle({3, 0, 0}, a, a, a), 9, 1e-15);
}

TEST(GroundTruth, WindingNumberIsOneInsideZeroOutsideAndFollowsOrientation) {
  const ConvexSolid cube = ConvexSolid::box({1, 1, 1});
  const double inside = windingNumber({0.3, -0.2, 0.9}, cube.vertices, cube.triangles);
  EXPECT_NEAR(std::abs(inside), 1, 1e-12);
  EXPECT_NEAR(windingNumber({1.5, 0, 0}, cube.vertices, cube.triangles), 0, 1e-12);
  std::vector<Triangle> flipped = cube.triangles;
  for (Triangle& t : flipped) std::swap(t[1], t[2]);
  EXPECT_NEAR(windingNumber({0.3, -0.2, 0.9}, cube.vertices, flipped), -inside, 1e-12);
}

TEST(GroundTruth, RejectsPiecesThatAreNotConvexSolids) {
  ConvexSolid dented = ConvexSolid::box({1, 1, 1});
  dented.vertices[7] = {0.2, 0.2, 0.2};  // a corner pushed inside
  EXPECT_THROW(SolidDistance{dented}, Error);
  ConvexSolid flat = ConvexSolid::box({1, 1, 1});
  for (Vec3& v : flat.vertices) v.y = 0;
  EXPECT_THROW(SolidDistance{flat}, Error);
  ConvexSolid broken = ConvexSolid::box({1, 1, 1});
  broken.vertices[0].x = std::nan("");
  EXPECT_THROW(SolidDistance{broken}, Error);
  ConvexSolid badIndex = ConvexSolid::box({1, 1, 1});
  badIndex.triangles[3][1] = 8;
  EXPECT_THROW(SolidDistance{badIndex}, Error);
}

Pose at(double x, double y, double z) {
  Pose pose;
  pose.translation = {x, y, z};
  return pose;
}

// A lone node, sampled as a one-node "surface": crossings and penetration without any soft body.
GroundTruth plateTruth() {
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box(kPlateHalf)), Pose{}, 0});
  return GroundTruth(std::move(pieces), false);
}

TEST(GroundTruth, CountsANodeThePlatePassesThroughInOneStep) {
  GroundTruth truth = plateTruth();
  truth.start({at(0, 1, 0)}, {{0.1, 0.5, 0.1}}, {});
  // The plate jumps from above the node to 0.3 m below it: no sample of the end state shows it.
  const GroundTruthStep& step = truth.update({at(0, 0.2, 0)}, {{0.1, 0.5, 0.1}}, {});
  EXPECT_EQ(step.crossings, 1);
  EXPECT_EQ(step.maxPenetration, 0);
  const GroundTruthRun run = truth.run();
  EXPECT_EQ(run.crossedNodes, 1);
  EXPECT_EQ(run.stillCrossed, 1);
}

TEST(GroundTruth, ANodeBesideTheFootprintOrPushedRoundTheRimDoesNotCross) {
  GroundTruth truth = plateTruth();
  truth.start({at(0, 1, 0)}, {{0.45, 0.5, 0}, {0.35, 0.9, 0}}, {});
  // The plate passes the first node, beside it. The second, under the plate near its rim, is
  // pushed out past the rim, then rises above the plate's level there: it went round, not through.
  truth.update({at(0, 0.95, 0)}, {{0.45, 0.5, 0}, {0.45, 0.9, 0}}, {});
  truth.update({at(0, 0.3, 0)}, {{0.45, 0.5, 0}, {0.45, 1.0, 0}}, {});
  const GroundTruthRun run = truth.run();
  EXPECT_EQ(run.crossedNodes, 0);
  EXPECT_EQ(run.stillCrossed, 0);
}

// The plate moves down across a node that lies on its side face, 0.05 mm inside it (a dynamic
// plate stopped at a sheet's pinned corner, generated seed 47279): within the tolerance of the rim
// the node slid along it. At 0.5 mm inside, it went through.
TEST(GroundTruth, ANodeSlidAlongTheRimWithinTheToleranceDoesNotCross) {
  const auto crossedAt = [](double x) {
    GroundTruth truth = plateTruth();
    truth.start({at(0, 0.52, 0)}, {{x, 0.5, 0}}, {});
    truth.update({at(0, 0.48, 0)}, {{x, 0.5, 0}}, {});
    return truth.run().crossedNodes;
  };
  EXPECT_EQ(crossedAt(0.4 - 0.5e-4), 0);
  EXPECT_EQ(crossedAt(0.4 - 5e-4), 1);
}

// A wedge blade, 2 mm thick at its back and sharp along its edge: near the edge the whole blade is
// thinner than the tolerance, and a node that passes through it there still crosses.
TEST(GroundTruth, ANodeThroughABladeNearItsEdgeCrosses) {
  ConvexSolid wedge;
  // Edge along z at x = 0.1; back at x = -0.1, 1 mm either side of y = 0.
  wedge.vertices = {{0.1, 0, -0.2}, {0.1, 0, 0.2}, {-0.1, -0.001, -0.2}, {-0.1, -0.001, 0.2},
                    {-0.1, 0.001, -0.2}, {-0.1, 0.001, 0.2}};
  wedge.triangles = {{0, 4, 1}, {1, 4, 5}, {0, 3, 2}, {0, 1, 3}, {2, 3, 5}, {2, 5, 4}, {0, 2, 4}, {1, 5, 3}};
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(wedge), Pose{}, 0});
  GroundTruth truth(std::move(pieces), false);
  ASSERT_EQ(SolidDistance(wedge).thinAxis(), 1);
  // 2 cm from the edge the blade is 0.2 mm thick: the node is 0.1 mm from either broad face.
  truth.start({at(0, 0.5, 0)}, {{0.08, 0.49, 0}}, {});
  truth.update({at(0, 0.48, 0)}, {{0.08, 0.49, 0}}, {});
  EXPECT_EQ(truth.run().crossedNodes, 1);
}

TEST(GroundTruth, ANodeThatCrossedAndCameBackIsNotStillCrossed) {
  GroundTruth truth = plateTruth();
  truth.start({at(0, 1, 0)}, {{0, 0.5, 0}}, {});
  truth.update({at(0, 0.3, 0)}, {{0, 0.5, 0}}, {});
  truth.update({at(0, 0.7, 0)}, {{0, 0.5, 0}}, {});
  const GroundTruthRun run = truth.run();
  EXPECT_EQ(run.crossedNodes, 1);
  EXPECT_EQ(run.stillCrossed, 0);
}

TEST(GroundTruth, NodesACutAddsAreFollowedFromWhereTheyAppear) {
  GroundTruth truth = plateTruth();
  truth.start({at(0, 1, 0)}, {{0.1, 0.5, 0.1}}, {});
  truth.update({at(0, 0.9, 0)}, {{0.1, 0.5, 0.1}}, {});
  EXPECT_THROW(truth.update({at(0, 0.8, 0)}, {{0.1, 0.5, 0.1}, {0.2, 0.5, 0}}, {}), Error);
  // A node appears under the plate; the plate then passes through it and through the first.
  truth.addNodes({{0.1, 0.5, 0.1}, {0.2, 0.5, 0}});
  const GroundTruthStep& step = truth.update({at(0, 0.2, 0)}, {{0.1, 0.5, 0.1}, {0.2, 0.5, 0}}, {});
  EXPECT_EQ(step.crossings, 2);
  // A node that appears below the plate, which it has passed, has not crossed it.
  truth.addNodes({{0.1, 0.5, 0.1}, {0.2, 0.5, 0}, {0, 0.3, 0}});
  EXPECT_EQ(truth.update({at(0, 0.1, 0)}, {{0.1, 0.5, 0.1}, {0.2, 0.5, 0}, {0, 0.3, 0}}, {}).crossings, 0);
  EXPECT_THROW(truth.addNodes({{0.1, 0.5, 0.1}}), Error);
}

// Two nodes the plate passes through in its second step; the first is pinned.
GroundTruthRun passOverAPinnedNode(bool immovablePlate) {
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box(kPlateHalf)), Pose{}, 0, immovablePlate});
  GroundTruth truth(std::move(pieces), false);
  const std::vector<Vec3> nodes{{0.3, 0.5, 0}, {-0.3, 0.5, 0}};
  truth.start({at(0, 1, 0)}, nodes, {}, {0});
  truth.update({at(0, 0.8, 0)}, nodes, {});
  truth.update({at(0, 0.3, 0)}, nodes, {});
  truth.update({at(0, 0.1, 0)}, nodes, {});
  return truth.run();
}

TEST(GroundTruth, AKinematicPlateThatReachesAPinnedNodeEndsTheJudgedSteps) {
  const GroundTruthRun run = passOverAPinnedNode(true);
  EXPECT_EQ(run.pinnedReachedStep, 2);
  EXPECT_EQ(run.unjudgedSteps, 2);
  EXPECT_EQ(run.steps, 3);
  EXPECT_EQ(run.crossedNodes, 0);  // the free node crossed in the same step: not judged either
}

TEST(GroundTruth, APinnedNodeADynamicToolPassesCounts) {
  // A tool the node can push could have given way: its crossing is a failure like any other.
  const GroundTruthRun run = passOverAPinnedNode(false);
  EXPECT_EQ(run.pinnedReachedStep, 0);
  EXPECT_EQ(run.unjudgedSteps, 0);
  EXPECT_EQ(run.crossedNodes, 2);
}

TEST(GroundTruth, PinnedNodeIndicesAreChecked) {
  GroundTruth truth = plateTruth();
  EXPECT_THROW(truth.start({at(0, 1, 0)}, {{0, 0.5, 0}}, {}, {1}), Error);
}

TEST(GroundTruth, PenetrationIsTheDepthOfTheDeepestSampleAndItsRms) {
  GroundTruth truth = plateTruth();
  truth.start({at(0, 0, 0)}, {{0, 0.5, 0}, {0.2, 0.5, 0}, {0, 0.5, 0.1}}, {});
  // Three nodes, each 7 mm into the 10 mm half thickness from above, 3 mm deep; their face's
  // centroid too.
  const std::vector<Vec3> nodes{{0, 0.007, 0}, {0.2, 0.007, 0}, {0, 0.007, 0.1}};
  const GroundTruthStep& step = truth.update({at(0, 0, 0)}, nodes, {{0, 1, 2}});
  EXPECT_NEAR(step.maxPenetration, 0.003, 1e-12);
  EXPECT_EQ(step.penetratingSamples, 4);
  EXPECT_NEAR(truth.run().rmsPenetration, 0.003, 1e-12);
}

TEST(GroundTruth, ToolInsideAClosedSurfaceIsSeen) {
  const ConvexSolid ball = ConvexSolid::box({1, 1, 1});  // a closed soft surface, as a cube
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box(kPlateHalf)), Pose{}, 0});
  GroundTruth truth(std::move(pieces), true);
  truth.start({at(0, 3, 0)}, ball.vertices, ball.triangles);
  EXPECT_FALSE(truth.update({at(0, 2, 0)}, ball.vertices, ball.triangles).toolInside);
  EXPECT_TRUE(truth.update({at(0, 0.5, 0)}, ball.vertices, ball.triangles).toolInside);
  const GroundTruthRun run = truth.run();
  EXPECT_EQ(run.toolInsideSteps, 1);
  EXPECT_TRUE(run.endsInside);
}

TEST(GroundTruth, CompoundPiecesAreMeasuredInTheirOwnFrames) {
  // Two halves side by side in the tool's frame; a node between them passes through neither.
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box({0.2, 0.01, 0.4})), at(-0.3, 0, 0), 0});
  pieces.push_back({SolidDistance(ConvexSolid::box({0.2, 0.01, 0.4})), at(0.3, 0, 0), 0});
  GroundTruth truth(std::move(pieces), false);
  truth.start({at(0, 1, 0)}, {{0, 0.5, 0}, {0.3, 0.5, 0}}, {});
  EXPECT_EQ(truth.update({at(0, 0, 0)}, {{0, 0.5, 0}, {0.3, 0.5, 0}}, {}).crossings, 1);
}

// Piercing: a soft triangle reaching deeper than the tolerance into a piece, whether or not any
// of its corners or its centroid is inside.

GroundTruth needleTruth() {
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box({0.5, 0.001, 0.001})), Pose{}, 0});  // a 2 mm bar along x
  return GroundTruth(std::move(pieces), false);
}

TEST(GroundTruth, ANeedleTipThroughALargeTriangleCountsAsPierced) {
  GroundTruth truth = needleTruth();
  // A triangle 2 m across in the plane x = 0.45, round the needle's tip (which reaches x = 0.5):
  // every corner and the centroid far outside the bar.
  const std::vector<Vec3> nodes{{0.45, -1, -1}, {0.45, 1, -1}, {0.45, 0, 1}};
  truth.start({Pose{}}, nodes, {{0, 1, 2}});
  const GroundTruthStep& step = truth.update({Pose{}}, nodes, {{0, 1, 2}});
  EXPECT_EQ(step.piercedFaces, 1);
  EXPECT_EQ(step.maxPenetration, 0);  // no sample shows it
  const GroundTruthRun run = truth.run();
  EXPECT_EQ(run.piercedSteps, 1);
  EXPECT_EQ(run.maxPiercedFaces, 1);
}

TEST(GroundTruth, ATriangleEdgeSlicingTheSolidCountsAsPierced) {
  GroundTruth truth = plateTruth();  // 0.8 x 0.02 x 0.8 m
  // A narrow triangle standing across the plate: its long edge passes through the plate's
  // thickness at x = 0.1, its corners 0.5 m above and below.
  const std::vector<Vec3> nodes{{0.1, 0.5, 0}, {0.1, -0.5, 0}, {0.1, 0.5, 0.01}};
  truth.start({Pose{}}, nodes, {{0, 1, 2}});
  EXPECT_EQ(truth.update({Pose{}}, nodes, {{0, 1, 2}}).piercedFaces, 1);
}

TEST(GroundTruth, ATriangleTouchingWithinTheToleranceIsNotPierced) {
  GroundTruth truth = plateTruth();
  // Lying on the plate's top face (y = 0.01), 0.05 mm into it, half the 0.1 mm tolerance; and a
  // second one crossing the plate's corner by as little.
  const double sink = 0.5 * GroundTruth::kDefaultTolerance;
  const std::vector<Vec3> nodes{{-0.2, 0.01 - sink, -0.2}, {0.2, 0.01 - sink, -0.2}, {0, 0.01 - sink, 0.2},
                                {0.4 - sink, 0.5, 0.4 - sink}, {0.4 - sink, -0.5, 0.4 - sink}, {0.9, 0, 0.9}};
  const std::vector<Triangle> faces{{0, 1, 2}, {3, 4, 5}};
  truth.start({Pose{}}, nodes, faces);
  EXPECT_EQ(truth.update({Pose{}}, nodes, faces).piercedFaces, 0);
  // Three times the tolerance deep, the lying one is pierced.
  std::vector<Vec3> deeper = nodes;
  for (int i = 0; i < 3; ++i) deeper[std::size_t(i)].y = 0.01 - 3 * GroundTruth::kDefaultTolerance;
  EXPECT_EQ(truth.update({Pose{}}, deeper, faces).piercedFaces, 1);
}

TEST(GroundTruth, TheToleranceIsAParameter) {
  std::vector<GroundTruthPiece> pieces;
  pieces.push_back({SolidDistance(ConvexSolid::box(kPlateHalf)), Pose{}, 0});
  GroundTruth truth(std::move(pieces), false, 0.005);
  const std::vector<Vec3> nodes{{-0.2, 0.008, -0.2}, {0.2, 0.008, -0.2}, {0, 0.008, 0.2}};  // 2 mm deep
  truth.start({Pose{}}, nodes, {{0, 1, 2}});
  EXPECT_EQ(truth.update({Pose{}}, nodes, {{0, 1, 2}}).piercedFaces, 0);
}

// Crossings along the tool's arc: the plate (0.4 m half side, thin along y) turns 90° about z in
// one step. A node at 45° in the xy plane, 0.5 m from the axis, is beyond the plate's reach all
// the way round, yet the chord between the plate's two frames (in which the node goes from
// (0.354, 0.354) to (0.354, -0.354)) crosses its mid-plane 0.354 m out, inside the plate. One
// 0.3 m out is swept by the plate.

Pose turnedAboutZ(double degrees) {
  Pose pose;
  pose.rotation = rotationAboutAxis({0, 0, 1}, degrees * kPi / 180);
  return pose;
}

TEST(GroundTruth, ANodeTheTurningPlateNeverReachesIsNotCrossed) {
  const double r = 0.5 / std::sqrt(2.0);
  const Vec3 node{r, r, 0};
  // The chord alone, as the test was before arcs: the same frames seen as one straight step.
  const SolidDistance plate(ConvexSolid::box(kPlateHalf));
  const Vec3 before = turnedAboutZ(0).applyInverse(node);
  const Vec3 after = turnedAboutZ(90).applyInverse(node);
  ASSERT_GT(before.y, 0);
  ASSERT_LT(after.y, 0);
  Vec3 onChord = before + (after - before) * (before.y / (before.y - after.y));
  onChord.y = 0;
  ASSERT_LT(plate.signedDistance(onChord), 0);  // the chord test would count it

  GroundTruth truth = plateTruth();
  truth.start({turnedAboutZ(0)}, {node}, {});
  EXPECT_EQ(truth.update({turnedAboutZ(90)}, {node}, {}).crossings, 0);
  EXPECT_EQ(truth.run().crossedNodes, 0);
}

TEST(GroundTruth, ANodeTheTurningPlateSweepsIsCrossed) {
  const double r = 0.3 / std::sqrt(2.0);
  GroundTruth truth = plateTruth();
  truth.start({turnedAboutZ(0)}, {{r, r, 0}}, {});
  EXPECT_EQ(truth.update({turnedAboutZ(90)}, {{r, r, 0}}, {}).crossings, 1);
  EXPECT_EQ(truth.run().crossedNodes, 1);
}

TEST(GroundTruth, ANodeRidingTheTurningPlatesFaceIsNotCrossed) {
  // 2 mm over the plate's top, 0.3 m out, at both ends of a step that turns the plate 150°: the
  // straight line between its two places in the world passes behind the plate on its arc, but in
  // the plate's frame it never moved.
  const Vec3 onTop{0.3, kPlateHalf.y + 0.002, 0};
  GroundTruth truth = plateTruth();
  truth.start({turnedAboutZ(0)}, {turnedAboutZ(0).apply(onTop)}, {});
  EXPECT_EQ(truth.update({turnedAboutZ(150)}, {turnedAboutZ(150).apply(onTop)}, {}).crossings, 0);
}

TEST(GroundTruth, AStepWithoutTurningIsOneInterval) {
  // A node the plate passes while moving straight: found once, as the single-interval test does;
  // the same with a turn of under 5°, which stays one interval.
  for (double degrees : {0.0, 4.0}) {
    GroundTruth truth = plateTruth();
    truth.start({at(0, 1, 0)}, {{0.1, 0.5, 0.1}}, {});
    Pose below = turnedAboutZ(degrees);
    below.translation = {0, 0.2, 0};
    EXPECT_EQ(truth.update({below}, {{0.1, 0.5, 0.1}}, {}).crossings, 1);
  }
}

// A closed surface folded through itself: two tetrahedra whose surfaces interpenetrate, as one
// body, and the same two apart.
TEST(GroundTruth, ASurfaceThroughItselfIsFound) {
  const std::vector<Triangle> faces{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {4, 6, 5}, {4, 5, 7}, {5, 6, 7}, {6, 4, 7}};
  std::vector<Vec3> apart{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 1}};
  EXPECT_FALSE(surfaceIntersectsItself(apart, faces));
  std::vector<Vec3> through = apart;
  for (std::size_t i = 4; i < 8; ++i) through[i] = through[i] - Vec3{2.8, -0.1, -0.1};
  EXPECT_TRUE(surfaceIntersectsItself(through, faces));
}

TEST(GroundTruth, AToolInsideASurfaceThroughItselfCountsApart) {
  // The plate's centre inside a small box-shaped closed surface, which is sound, then the same
  // surface with a second closed sheet passing through it.
  const auto closedPlateTruth = [] {
    std::vector<GroundTruthPiece> pieces;
    pieces.push_back({SolidDistance(ConvexSolid::box(kPlateHalf)), Pose{}, 0});
    return GroundTruth(std::move(pieces), true);
  };
  GroundTruth truth = closedPlateTruth();
  const ConvexSolid cube = ConvexSolid::box({0.5, 0.5, 0.5});
  std::vector<Vec3> nodes = cube.vertices;
  std::vector<Triangle> faces = cube.triangles;
  truth.start({Pose{}}, nodes, faces);
  EXPECT_TRUE(truth.update({Pose{}}, nodes, faces).toolInside);
  for (const Vec3& v : cube.vertices) nodes.push_back(v * 0.5 + Vec3{0.4, 0.1, 0.1});
  for (const Triangle& t : cube.triangles) faces.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  GroundTruth folded = closedPlateTruth();
  folded.start({Pose{}}, nodes, faces);
  const GroundTruthStep& step = folded.update({Pose{}}, nodes, faces);
  EXPECT_FALSE(step.toolInside);
  EXPECT_TRUE(step.selfIntersecting);
  EXPECT_EQ(folded.run().selfIntersectingSteps, 1);
  // The fold untangles with the plate still within: still the fold's doing, not the tool's.
  nodes.resize(8);
  faces.resize(12);
  for (std::size_t i = 0; i < 8; ++i) nodes.push_back(cube.vertices[i] * 0.5 + Vec3{3, 0, 0});
  for (const Triangle& t : cube.triangles) faces.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  EXPECT_TRUE(folded.update({Pose{}}, nodes, faces).selfIntersecting);
  EXPECT_EQ(folded.run().toolInsideSteps, 0);
  // Once the plate has left, inside counts again.
  const GroundTruthStep& away = folded.update({at(10, 0, 0)}, nodes, faces);
  EXPECT_FALSE(away.toolInside || away.selfIntersecting);
  EXPECT_TRUE(folded.update({Pose{}}, nodes, faces).toolInside);
}

}  // namespace
}  // namespace thintool::eval
