// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The scene generator: the same seed gives the same scene, and a thousand seeds stay inside the
// ranges its header documents while reaching every mesh, every tool, kinematic and dynamic.

#include <SceneGenerator.h>

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>

namespace thintool::eval {
namespace {

using namespace generated;

const std::string kScenes = THINTOOL_EVAL_SCENES;

// Inside [low, high], with room for the rounding of a value computed from a drawn one.
void expectWithin(double value, double low, double high, const std::string& what, std::uint64_t seed) {
  const double slack = 1e-9 * std::max(std::abs(low), std::abs(high));
  EXPECT_TRUE(value >= low - slack && value <= high + slack)
      << what << " = " << value << " outside [" << low << ", " << high << "] for seed " << seed;
}

std::string toolKindOf(const ToolSpec& tool) {
  if (tool.pieces.size() == 2) return "jaws";
  if (tool.pieces[0].kind == ToolPieceSpec::Kind::Hull) return "blade";
  const Vec3& h = tool.pieces[0].halfExtents;
  return h.y == h.z && h.y <= kMaxNeedleWidth / 2 && h.x >= kMinNeedleLength / 2 ? "needle" : "plate";
}

TEST(SceneGenerator, TheSameSeedGivesTheSameScene) {
  for (std::uint64_t seed : {1ULL, 2ULL, 77ULL, 123456789ULL, 18446744073709551615ULL}) {
    const std::string first = describeScene(generateScene(seed, kScenes));
    EXPECT_EQ(first, describeScene(generateScene(seed, kScenes)));
    EXPECT_NE(first.find("generated-" + std::to_string(seed) + ":"), std::string::npos) << first;
  }
  EXPECT_NE(describeScene(generateScene(1, kScenes)), describeScene(generateScene(2, kScenes)));
}

TEST(SceneGenerator, AThousandSeedsStayInTheirRangesAndCoverEveryKind) {
  std::set<SoftBodySpec::Mesh> meshes;
  std::set<std::string> tools;
  int dynamic = 0, kinematic = 0, turning = 0, holds = 0, largeEllipsoids = 0;
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const SceneSpec scene = generateScene(seed, kScenes);
    EXPECT_EQ(scene.algorithm, AlgorithmKind::Swept);
    EXPECT_EQ(scene.substeps, 1);
    expectWithin(scene.timeStep, kMinTimeStep, kMaxTimeStep, "dt", seed);
    expectWithin(scene.settleSeconds, kMinSettleSeconds, kMaxSettleSeconds, "settle", seed);
    const long steps = std::lround(scene.duration / scene.timeStep);
    EXPECT_GE(steps, 1);
    EXPECT_LE(steps, kMaxSteps) << seed;
    expectWithin(scene.duration, 0, kMaxSeconds, "duration", seed);
    // The work budget holds unless the body is so large that even the coarsest step and the
    // fewest measured steps pass it.
    const double nodes = scene.soft.mesh == SoftBodySpec::Mesh::Ellipsoid ? scene.soft.resolution + 3
                         : scene.soft.mesh == SoftBodySpec::Mesh::Obj
                             ? double(scene.soft.objMesh.vertices.size())
                         : scene.soft.mesh == SoftBodySpec::Mesh::Sheet
                             ? double(scene.soft.nodesPerSide * scene.soft.nodesPerSide)
                             : std::pow(scene.soft.tetraCells + 1, 3);
    const double work = nodes * double(std::lround(scene.settleSeconds / scene.timeStep) + steps);
    if (work > kWorkBudget * 1.001) {
      EXPECT_LE(steps, kMinMeasuredSteps) << seed;
      EXPECT_NEAR(scene.timeStep, kMaxTimeStep, 1e-12) << seed;
    }

    const SoftBodySpec& soft = scene.soft;
    meshes.insert(soft.mesh);
    switch (soft.mesh) {
      case SoftBodySpec::Mesh::Ellipsoid: {
        const int faces = 2 * (soft.resolution + 1);
        expectWithin(faces, kMinEllipsoidFaces, kMaxEllipsoidFaces, "ellipsoid faces", seed);
        EXPECT_EQ(soft.exactHull, faces > kExactHullFaces) << seed;
        largeEllipsoids += faces > 8000;
        for (int axis = 0; axis < 3; ++axis) expectWithin(soft.radius[axis], kMinRadius, kMaxRadius, "radius", seed);
        EXPECT_EQ(soft.centre.y, soft.radius.y) << seed;  // resting on the ground
        break;
      }
      case SoftBodySpec::Mesh::Obj:
        EXPECT_EQ(soft.objFile, "vessel.obj");
        EXPECT_FALSE(soft.objMesh.triangles.empty());
        expectWithin(soft.scale, kMinVesselScale, kMaxVesselScale, "vessel scale", seed);
        break;
      case SoftBodySpec::Mesh::Sheet:
        expectWithin(soft.nodesPerSide, kMinSheetNodes, kMaxSheetNodes, "sheet nodes", seed);
        expectWithin(soft.sheetSize, kMinSheetSize, kMaxSheetSize, "sheet size", seed);
        expectWithin(soft.centre.y, kMinSheetHeight, kMaxSheetHeight, "sheet height", seed);
        EXPECT_EQ(soft.pressure, 0) << seed;
        break;
      case SoftBodySpec::Mesh::Tetra:
        expectWithin(soft.tetraCells, kMinTetraCells, kMaxTetraCells, "tetra cells", seed);
        expectWithin(soft.sheetSize, kMinTetraEdge, kMaxTetraEdge, "tetra edge", seed);
        EXPECT_EQ(soft.pressure, 0) << seed;  // its tetrahedra hold it up
        break;
    }
    expectWithin(soft.linearStiffness, kMinLinearStiffness, kMaxLinearStiffness, "kLST", seed);
    expectWithin(soft.pressure, 0, kMaxPressure, "kPR", seed);
    ASSERT_TRUE(soft.positionIterations.has_value());
    expectWithin(*soft.positionIterations, kMinPositionIterations, kMaxPositionIterations, "piterations", seed);
    ASSERT_TRUE(soft.margin.has_value());
    expectWithin(*soft.margin, kMinMargin, kMaxMargin, "margin", seed);
    expectWithin(soft.mass, kMinSoftMass, kMaxSoftMass, "soft mass", seed);
    expectWithin(soft.friction, kMinFriction, kMaxFriction, "kDF", seed);

    ASSERT_EQ(scene.tools.size(), 1u);
    const ToolSpec& tool = scene.tools[0];
    const std::string kind = toolKindOf(tool);
    tools.insert(kind);
    if (kind == "plate" || kind == "jaws") {
      for (const ToolPieceSpec& piece : tool.pieces) {
        const double wide = kind == "plate" ? kMaxPlateWidth : kMaxJawWidth;
        const double narrow = kind == "plate" ? kMinPlateWidth : kMinJawWidth;
        expectWithin(2 * piece.halfExtents.y, kMinPlateThickness, kMaxPlateThickness, "thickness", seed);
        expectWithin(2 * piece.halfExtents.x, narrow, wide, "width", seed);
        expectWithin(2 * piece.halfExtents.z, narrow, wide, "depth", seed);
      }
      if (kind == "jaws") {
        const double gap = tool.pieces[0].offset.translation.y - tool.pieces[1].offset.translation.y -
                           2 * tool.pieces[0].halfExtents.y;
        expectWithin(gap, kMinJawGap, kMaxJawGap, "jaw gap", seed);
        EXPECT_EQ(tool.pieces[0].offset.translation.y, -tool.pieces[1].offset.translation.y) << seed;
      }
    } else if (kind == "needle") {
      expectWithin(2 * tool.pieces[0].halfExtents.y, kMinNeedleWidth, kMaxNeedleWidth, "needle width", seed);
      expectWithin(2 * tool.pieces[0].halfExtents.x, kMinNeedleLength, kMaxNeedleLength, "needle length", seed);
    } else {
      const SolidDistance blade(tool.pieces[0].hull);  // a closed convex solid, or it throws
      expectWithin(2 * blade.halfExtents().z, kMinBladeLength, kMaxBladeLength, "blade length", seed);
      expectWithin(2 * blade.halfExtents().y, kMinBladeHeight, kMaxBladeHeight, "blade height", seed);
      expectWithin(2 * blade.halfExtents().x, kMinBladeThickness, kMaxBladeThickness, "blade thickness", seed);
    }
    if (tool.mass > 0) {
      ++dynamic;
      expectWithin(tool.mass, kMinToolMass, kMaxToolMass, "tool mass", seed);
    } else {
      ++kinematic;
    }

    const TrajectorySpec& path = tool.trajectory;
    EXPECT_EQ(path.kind, TrajectorySpec::Kind::Waypoints);
    EXPECT_TRUE(path.plannedBodyBox.has_value());
    expectWithin(double(path.waypoints.size()) - 1, kMinSegments, kMaxSegments, "segments", seed);
    bool turns = false;
    for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
      const TrajectorySpec::Waypoint& a = path.waypoints[i - 1];
      const TrajectorySpec::Waypoint& b = path.waypoints[i];
      ASSERT_GT(b.time, a.time) << seed;
      const double stepsInSegment = (b.time - a.time) / scene.timeStep;
      expectWithin(length(b.position - a.position) / (b.time - a.time), 0, kMaxSpeed, "speed", seed);
      expectWithin(length(b.rotation - a.rotation) / stepsInSegment, 0, kMaxTurnDegreesPerStep, "turn a step", seed);
      turns = turns || b.rotation != a.rotation;
      holds += b.position == a.position && b.rotation == a.rotation;
    }
    turning += turns;
    // The first segment moves, so that a dynamic tool is launched.
    EXPECT_NE(path.waypoints[0].position, path.waypoints[1].position) << seed;
  }
  EXPECT_EQ(meshes.size(), 4u);
  EXPECT_EQ(tools, (std::set<std::string>{"plate", "needle", "blade", "jaws"}));
  EXPECT_GT(dynamic, 100);
  EXPECT_GT(kinematic, 700);
  EXPECT_GT(turning, 200);
  EXPECT_GT(1000 - turning, 200);
  EXPECT_GT(holds, 50);
  EXPECT_GT(largeEllipsoids, 10);
  EXPECT_LT(largeEllipsoids, 100);  // rare enough to keep the runs short
}

// The scene without the text pose matching adds to its description.
std::string withoutPoseMatching(std::string text) {
  const std::size_t at = text.find(" kMT ");
  if (at != std::string::npos) text.erase(at, 9);  // " kMT 0.xx"
  return text;
}

TEST(SceneGenerator, BulletKindsLeaveTheRestOfEachSceneAsItWas) {
  GeneratorOptions kindsOn;
  kindsOn.bulletKinds = true;
  std::set<std::string> roundTools;
  int poseMatched = 0;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    const SceneSpec plain = generateScene(seed, kScenes);
    const SceneSpec kinds = generateScene(seed, kScenes, kindsOn);
    EXPECT_EQ(plain.soft.poseMatching, 0) << seed;
    EXPECT_TRUE(plain.soft.pinnedCorners) << seed;
    if (!kinds.soft.pinnedCorners) continue;  // a draped cloth: DrapedClothFallsOnAToolThatWaitsUnderIt
    if (kinds.soft.poseMatching != 0) {
      ++poseMatched;
      expectWithin(kinds.soft.poseMatching, kMinPoseMatching, kMaxPoseMatching, "kMT", seed);
    }
    const ToolSpec& tool = kinds.tools.at(0);
    if (tool.name == plain.tools.at(0).name) {
      // The same tool: the same scene, down to the path, but for the pose matching and a cut.
      SceneSpec uncut = kinds;
      uncut.soft.cut.reset();
      EXPECT_EQ(withoutPoseMatching(describeScene(uncut)), describeScene(plain)) << seed;
      continue;
    }
    roundTools.insert(tool.name);
    EXPECT_EQ(kinds.timeStep, plain.timeStep) << seed;
    EXPECT_EQ(kinds.soft.mesh, plain.soft.mesh) << seed;
    EXPECT_EQ(tool.mass, plain.tools[0].mass) << seed;
    // Every round piece is a closed convex solid (or SolidDistance throws), as wide as drawn.
    const bool ball = tool.name == "ball";
    const SolidDistance round(tool.pieces.back().hull);
    const Vec3 half = round.halfExtents();
    if (tool.name == "capsule") {
      expectWithin(half.y, kMinCapsuleRadius, kMaxCapsuleRadius, "capsule radius", seed);
      expectWithin(2 * half.x - 2 * half.y, kMinCapsuleLength, kMaxCapsuleLength, "capsule length", seed);
    } else {
      expectWithin(half.x, kMinBallRadius, kMaxBallRadius, "ball radius", seed);
      EXPECT_NEAR(half.x, half.y, 1e-12) << seed;
      EXPECT_EQ(tool.pieces.size(), ball ? 1u : 2u) << seed;
    }
  }
  EXPECT_EQ(roundTools, (std::set<std::string>{"ball", "capsule", "box and ball"}));
  EXPECT_GT(poseMatched, 50);
  EXPECT_LT(poseMatched, 150);
}

TEST(SceneGenerator, DrapedClothFallsOnAToolThatWaitsUnderIt) {
  GeneratorOptions kindsOn;
  kindsOn.bulletKinds = true;
  int draped = 0, sheets = 0, moved = 0;
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const SceneSpec plain = generateScene(seed, kScenes);
    const SceneSpec scene = generateScene(seed, kScenes, kindsOn);
    sheets += plain.soft.mesh == SoftBodySpec::Mesh::Sheet;
    if (scene.soft.pinnedCorners) continue;
    ++draped;
    EXPECT_EQ(plain.soft.mesh, SoftBodySpec::Mesh::Sheet) << seed;
    EXPECT_EQ(scene.soft.mesh, SoftBodySpec::Mesh::Sheet) << seed;
    EXPECT_EQ(scene.timeStep, plain.timeStep) << seed;
    EXPECT_EQ(scene.settleSeconds, 0) << seed;
    EXPECT_TRUE(scene.ground) << seed;
    const ToolSpec& tool = scene.tools.at(0);
    EXPECT_EQ(tool.mass, 0) << seed;
    const std::vector<TrajectorySpec::Waypoint>& points = tool.trajectory.waypoints;
    ASSERT_GE(points.size(), 2u) << seed;
    // The tool starts under the cloth, wholly, and waits there until the cloth has fallen onto it.
    double top = -1e9, reach = 0;
    const Pose start = poseOf(points[0].position, points[0].rotation);
    for (const ToolPieceSpec& piece : tool.pieces) {
      for (const Vec3& v : solidOf(piece).vertices) {
        top = std::max(top, start.apply(piece.offset.apply(v)).y);
        reach = std::max(reach, length(piece.offset.apply(v)));
      }
    }
    const double cloth = scene.soft.centre.y;
    EXPECT_LT(top, cloth) << seed;
    EXPECT_EQ(points[1].position, points[0].position) << seed;
    EXPECT_EQ(points[1].rotation, points[0].rotation) << seed;
    const double gravity = length(scene.gravity);
    EXPECT_GE(0.5 * gravity * points[1].time * points[1].time, cloth - points[0].position.y - reach) << seed;
    // It lands within the run, and before the tool moves.
    const double fallTime = std::sqrt(2 * (cloth - top) / gravity);
    EXPECT_LT(fallTime, scene.duration) << seed;
    EXPECT_LE(fallTime, points[1].time) << seed;
    // Then it only lifts, its centre far enough above the ground for any turn.
    for (std::size_t i = 1; i < points.size(); ++i) {
      EXPECT_GE(points[i].position.y, points[i - 1].position.y) << seed;
      moved += points[i].position != points[i - 1].position;
    }
    EXPECT_GE(points[0].position.y, reach + *scene.soft.margin + kDrapeGroundGap - 1e-12) << seed;
  }
  EXPECT_GT(draped, sheets * kDrapeChance / 2);
  EXPECT_LT(draped, sheets * kDrapeChance * 1.5);
  EXPECT_GT(moved, draped / 2);
}

TEST(SceneGenerator, CutClothIsASheetThatIsNotPoseMatchedCutThroughItsMiddle) {
  GeneratorOptions kindsOn;
  kindsOn.bulletKinds = true;
  int cut = 0, candidates = 0, drapedAndCut = 0;
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    EXPECT_FALSE(generateScene(seed, kScenes).soft.cut) << seed;
    const SceneSpec scene = generateScene(seed, kScenes, kindsOn);
    const SoftBodySpec& soft = scene.soft;
    candidates += soft.mesh == SoftBodySpec::Mesh::Sheet && soft.poseMatching == 0;
    if (!soft.cut) continue;
    ++cut;
    drapedAndCut += !soft.pinnedCorners;
    EXPECT_EQ(soft.mesh, SoftBodySpec::Mesh::Sheet) << seed;
    EXPECT_EQ(soft.poseMatching, 0) << seed;
    expectWithin(soft.cut->time, 0.2 * scene.duration, 0.8 * scene.duration, "cut time", seed);
    expectWithin(soft.cut->halfLength, kMinCutShare * soft.sheetSize / 2, kMaxCutShare * soft.sheetSize / 2,
                 "cut half length", seed);
    EXPECT_NEAR(length(soft.cut->direction), 1, 1e-12) << seed;
    EXPECT_EQ(soft.cut->direction.y, 0) << seed;
    expectWithin(std::abs(soft.cut->point.x - soft.centre.x), 0, soft.sheetSize / 4, "cut point x", seed);
    expectWithin(std::abs(soft.cut->point.z - soft.centre.z), 0, soft.sheetSize / 4, "cut point z", seed);
  }
  EXPECT_GT(cut, candidates * kCutChance / 2);
  EXPECT_LT(cut, candidates * kCutChance * 1.5);
  EXPECT_GT(drapedAndCut, 0);
}

TEST(SceneGenerator, SeedFilesSkipCommentsAndNameTheirBadLines) {
  const std::string path = ::testing::TempDir() + "/seeds.txt";
  {
    std::ofstream out(path);
    out << "# a header\n\n17  # crossed 3 nodes\n  42\n";
  }
  EXPECT_EQ(readSeedFile(path), (std::vector<std::uint64_t>{17, 42}));
  {
    std::ofstream out(path);
    out << "17\nseventeen\n";
  }
  try {
    readSeedFile(path);
    ADD_FAILURE() << "a bad seed was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("seeds.txt:2:"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

TEST(SceneGenerator, TheRegressionFileReads) {
  EXPECT_NO_THROW(readSeedFile(std::string(THINTOOL_EVAL_GENERATED) + "/regressions.txt"));
}

}  // namespace
}  // namespace thintool::eval
