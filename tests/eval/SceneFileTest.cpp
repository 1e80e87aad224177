// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Scene files: every shipped scene loads; every kind of mistake is reported with the file, the
// line, the field and what was expected; overrides and trajectories do what the format says.

#include <SceneFile.h>

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <dirent.h>

#include <cmath>
#include <fstream>
#include <string>

namespace thintool::eval {
namespace {

const std::string kScenes = THINTOOL_EVAL_SCENES;

const char* kMinimal = R"({
  "name": "minimal",
  "step": {"dt": "1/60", "duration": 0.5},
  "soft": {"mesh": "ellipsoid", "resolution": 63},
  "tools": [
    {"name": "plate",
     "shape": {"type": "box", "half_extents": [0.4, 0.01, 0.4]},
     "trajectory": {"type": "constant_velocity", "start": [0, 2.5, 0], "speed": 2, "distance": 0.5}}
  ]
})";

std::string errorOf(const std::string& text, const std::vector<Override>& overrides = {}) {
  try {
    parseScene(text, "scene.json", kScenes, overrides);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(SceneFile, EveryShippedSceneLoads) {
  DIR* folder = opendir(kScenes.c_str());
  ASSERT_NE(folder, nullptr);
  int scenes = 0;
  while (dirent* entry = readdir(folder)) {
    const std::string name = entry->d_name;
    if (name.size() < 5 || name.substr(name.size() - 5) != ".json") continue;
    SCOPED_TRACE(name);
    const SceneSpec scene = loadScene(kScenes + "/" + name);
    EXPECT_FALSE(scene.tools.empty());
    EXPECT_GT(scene.duration, 0);
    ++scenes;
  }
  closedir(folder);
  EXPECT_GE(scenes, 6);
}

TEST(SceneFile, ReadsTheMinimalSceneWithDefaults) {
  const SceneSpec scene = parseScene(kMinimal, "scene.json", kScenes);
  EXPECT_EQ(scene.name, "minimal");
  EXPECT_DOUBLE_EQ(scene.timeStep, 1.0 / 60);
  EXPECT_EQ(scene.algorithm, AlgorithmKind::Swept);
  EXPECT_EQ(scene.soft.mesh, SoftBodySpec::Mesh::Ellipsoid);
  EXPECT_EQ(scene.soft.resolution, 63);
  ASSERT_EQ(scene.tools.size(), 1u);
  EXPECT_EQ(scene.tools[0].pieces[0].halfExtents.y, 0.01);
  EXPECT_DOUBLE_EQ(endTime(scene.tools[0].trajectory), 0.25);
  EXPECT_DOUBLE_EQ(poseAt(scene.tools[0].trajectory, 0.1).translation.y, 2.3);
  EXPECT_DOUBLE_EQ(poseAt(scene.tools[0].trajectory, 9).translation.y, 2.0);  // held at the end
}

TEST(SceneFile, ErrorsNameFileLineFieldAndWhatWasExpected) {
  std::string error = errorOf(replaced(kMinimal, "\"speed\": 2", "\"speed\": \"fast\""));
  EXPECT_NE(error.find("scene.json:8:"), std::string::npos) << error;
  EXPECT_NE(error.find("tools[0].trajectory.speed"), std::string::npos) << error;
  EXPECT_NE(error.find("number"), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "\"speed\": 2", "\"sped\": 2"));
  EXPECT_NE(error.find("sped"), std::string::npos) << error;
  EXPECT_NE(error.find("speed"), std::string::npos) << error;  // the expected names are listed

  error = errorOf(replaced(kMinimal, "\"type\": \"box\"", "\"type\": \"bx\""));
  EXPECT_NE(error.find("tools[0].shape.type"), std::string::npos) << error;
  EXPECT_NE(error.find("\"hull\""), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "[0.4, 0.01, 0.4]", "[0.4, 0, 0.4]"));
  EXPECT_NE(error.find("half_extents"), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "\"dt\": \"1/60\"", "\"dt\": \"1/0\""));
  EXPECT_NE(error.find("step.dt"), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "\"mesh\": \"ellipsoid\", \"resolution\": 63", "\"mesh\": \"ellipsoid\""
                                                                                     ", \"resolution\": 2.5"));
  EXPECT_NE(error.find("soft.resolution"), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "\"name\": \"minimal\",", "\"name\": \"minimal\", \"algorithm\": \"fast\","));
  EXPECT_NE(error.find("\"swept\""), std::string::npos) << error;

  error = errorOf(replaced(kMinimal, "\"soft\"", "\"sfot\""));
  EXPECT_NE(error.find("sfot"), std::string::npos) << error;

  // Found by fuzz_json: a tool that never moves, no hold and no duration made a scene of 0 s.
  error = errorOf(R"({"step": {"hold": 0}, "soft": {"mesh": "ellipsoid"}, "tools": [{"shape": {"type": "box",
    "half_extents": [1, 1, 1]}, "trajectory": {"type": "waypoints", "points": [{"t": 0, "position": [0, 5, 0]}]}}]})");
  EXPECT_NE(error.find("lasts 0 s"), std::string::npos) << error;

  error = errorOf("{\"soft\": {\"mesh\": \"ellipsoid\"}, \"tools\": []}");
  EXPECT_NE(error.find("tools"), std::string::npos) << error;

  error = errorOf("{\"soft\": {\"mesh\": \"ellipsoid\"},\n \"tools\": [ }");
  EXPECT_NE(error.find("scene.json:2:"), std::string::npos) << error;  // a JSON syntax error
}

TEST(SceneFile, OverridesReplaceAddAndCheckFields) {
  SceneSpec scene = parseScene(kMinimal, "scene.json", kScenes,
                               {parseOverride("step.dt=1/240"), parseOverride("algorithm=paper"),
                                parseOverride("tools[0].trajectory.speed=5"), parseOverride("thintool.force=true")});
  EXPECT_DOUBLE_EQ(scene.timeStep, 1.0 / 240);
  EXPECT_EQ(scene.algorithm, AlgorithmKind::Paper);
  EXPECT_EQ(scene.tools[0].trajectory.speed, 5);
  EXPECT_TRUE(scene.force);

  EXPECT_NE(errorOf(kMinimal, {parseOverride("tools[3].trajectory.speed=5")}).find("tools[3]"), std::string::npos);
  EXPECT_NE(errorOf(kMinimal, {parseOverride("algorithm=quick")}).find("\"paper\""), std::string::npos);
  EXPECT_NE(errorOf(kMinimal, {parseOverride("step.dtt=0.1")}).find("dtt"), std::string::npos);
  EXPECT_THROW(parseOverride("no-equals-sign"), Error);
}

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(SceneFile, WaypointsAndCsvTrajectoriesInterpolateAndHold) {
  const std::string csv = writeFile("path.csv", "t,x,y,z,rx,ry,rz\n0,0,2,0,0,0,0\n1,1,2,0,0,0,90\n");
  std::string text = replaced(kMinimal, R"({"type": "constant_velocity", "start": [0, 2.5, 0], "speed": 2, "distance": 0.5})",
                              "{\"type\": \"csv\", \"file\": \"" + csv + "\"}");
  text = replaced(text, "\"duration\": 0.5", "\"hold\": 0.5");  // run until the trajectory ends, plus the hold
  SceneSpec scene = parseScene(text, "scene.json", kScenes);
  const Pose half = poseAt(scene.tools[0].trajectory, 0.5);
  EXPECT_DOUBLE_EQ(half.translation.x, 0.5);
  // 45° about z: x turns towards y.
  EXPECT_NEAR(half.apply({1, 0, 0}).y - half.translation.y, std::sqrt(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(poseAt(scene.tools[0].trajectory, 2).translation.x, 1);
  EXPECT_DOUBLE_EQ(scene.duration, 1.5);

  const std::string bad = writeFile("bad.csv", "t,x,y,z\n0,0,2,0\n0.5,1,2\n");
  text = replaced(kMinimal, R"({"type": "constant_velocity", "start": [0, 2.5, 0], "speed": 2, "distance": 0.5})",
                  "{\"type\": \"csv\", \"file\": \"" + bad + "\"}");
  EXPECT_NE(errorOf(text).find("bad.csv:3:"), std::string::npos) << errorOf(text);

  text = replaced(kMinimal, R"({"type": "constant_velocity", "start": [0, 2.5, 0], "speed": 2, "distance": 0.5})",
                  R"({"type": "waypoints", "points": [{"t": 0, "position": [0, 2, 0]}, {"t": 0, "position": [0, 1, 0]}]})");
  EXPECT_NE(errorOf(text).find("points[1].t"), std::string::npos) << errorOf(text);
}

TEST(SceneFile, HullsMustBeConvexAndOtherFilesMustExist) {
  const std::string dented = writeFile("dented.obj",
                                       "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\n"
                                       "v 0.1 0.1 0.1\nf 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
  std::string text = replaced(kMinimal, R"({"type": "box", "half_extents": [0.4, 0.01, 0.4]})",
                              "{\"type\": \"hull\", \"file\": \"" + dented + "\"}");
  std::string error = errorOf(text);
  EXPECT_NE(error.find("tools[0].shape.file"), std::string::npos) << error;
  EXPECT_NE(error.find("not convex"), std::string::npos) << error;

  text = replaced(kMinimal, R"({"type": "box", "half_extents": [0.4, 0.01, 0.4]})",
                  R"({"type": "hull", "file": "missing.obj"})");
  EXPECT_NE(errorOf(text).find("cannot read"), std::string::npos) << errorOf(text);

  // The shipped blade, scaled: its solid is scaled too.
  text = replaced(kMinimal, R"({"type": "box", "half_extents": [0.4, 0.01, 0.4]})",
                  R"({"type": "hull", "file": "blade.obj", "scale": 2})");
  const SceneSpec scene = parseScene(text, "scene.json", kScenes);
  const SolidDistance blade(solidOf(scene.tools[0].pieces[0]));
  EXPECT_NEAR(blade.halfExtents().x, 0.6, 1e-12);
  EXPECT_EQ(blade.thinAxis(), 2);
}

TEST(SceneFile, CompoundToolsListTheirPartsWithOffsets) {
  const std::string text = replaced(kMinimal, R"({"type": "box", "half_extents": [0.4, 0.01, 0.4]})",
                                    R"({"type": "compound", "parts": [
      {"type": "box", "half_extents": [0.2, 0.01, 0.4], "offset": {"position": [-0.2, 0, 0]}},
      {"type": "box", "half_extents": [0.2, 0.01, 0.4], "offset": {"position": [0.2, 0, 0], "rotation": [0, 0, 10]}}]})");
  const SceneSpec scene = parseScene(text, "scene.json", kScenes);
  ASSERT_EQ(scene.tools[0].pieces.size(), 2u);
  EXPECT_EQ(scene.tools[0].pieces[0].offset.translation.x, -0.2);
  EXPECT_NEAR(scene.tools[0].pieces[1].offset.rotation.row[0].y, -std::sin(10 * kPi / 180), 1e-12);
}

}  // namespace
}  // namespace thintool::eval


namespace thintool::eval {
namespace {

TEST(SceneFile, TheExactHullIsAnEllipsoidOption) {
  const SceneSpec scene = parseScene(
      R"({"soft": {"mesh": "ellipsoid", "resolution": 2047, "exact_hull": true}, "tools": [{"shape": {"type": "box",
      "half_extents": [1, 1, 1]}, "trajectory": {"type": "constant_velocity", "start": [0, 5, 0]}}]})",
      "scene.json", kScenes);
  EXPECT_TRUE(scene.soft.exactHull);
  EXPECT_EQ(scene.soft.resolution, 2047);
  const std::string error = [] {
    try {
      parseScene(R"({"soft": {"mesh": "ellipsoid", "exact_hull": 1}, "tools": []})", "scene.json", kScenes);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(error.find("soft.exact_hull"), std::string::npos) << error;
}

}  // namespace
}  // namespace thintool::eval
