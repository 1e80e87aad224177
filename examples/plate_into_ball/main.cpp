// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example shows the paper's first scene, headless: a thin plate (or a needle) pressed into
// a 128-face soft ball, with stock Bullet's soft–rigid contact and with ThinTool side by side.
// It prints one table whose accuracy columns and time column come from the same runs.
//
//   plate_into_ball [--tool plate|needle] [--speeds 0.1,1,5,20] [--steps 60,1000]
//                   [--world soft-rigid|soft-multibody|deformable]
//   plate_into_ball [--tool plate|needle] --view                       (the viewer, where built)
//   plate_into_ball [--tool plate|needle] [--stock] --screenshot FILE.png [--after N]

#include "SoftBallScene.h"
#ifdef THINTOOL_HAVE_VIEWER
#include "BallSceneView.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

using namespace thintool::scenes;

namespace {

std::vector<double> parseList(const char* text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    values.push_back(std::atof(item.c_str()));
  }
  return values;
}

int usage() {
  std::fprintf(stderr, "usage: plate_into_ball [--tool plate|needle] [--speeds 0.1,1,5,20] [--steps 60,1000]\n"
                       "                       [--world soft-rigid|soft-multibody|deformable]\n"
                       "       plate_into_ball [--tool plate|needle] [--stock] --view | --screenshot FILE.png [--after N]\n"
                       "  --steps lists time steps as steps per second; --view and --screenshot need the viewer\n"
                       "  (built where GLFW, OpenGL, Dear ImGui and stb are installed); --after: steps before the\n"
                       "  screenshot (60); --stock: stock Bullet (E) instead of ThinTool; --world: the Bullet world\n"
                       "  (btSoftRigidDynamicsWorld by default; in the deformable world the ball is a mass-spring body\n"
                       "  without pressure)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  ToolShape shape = ToolShape::Plate;
  std::vector<double> speeds{0.1, 1, 5, 20};
  std::vector<double> rates{60, 1000};
  WorldKind world = WorldKind::SoftRigid;
  bool view = false;
  bool stock = false;
  std::string screenshot;
  int screenshotSteps = 60;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--tool") == 0 && hasValue) {
      const std::string name = argv[++i];
      if (name != "plate" && name != "needle") return usage();
      shape = name == "plate" ? ToolShape::Plate : ToolShape::Needle;
    } else if (std::strcmp(argv[i], "--speeds") == 0 && hasValue) {
      speeds = parseList(argv[++i]);
    } else if (std::strcmp(argv[i], "--steps") == 0 && hasValue) {
      rates = parseList(argv[++i]);
    } else if (std::strcmp(argv[i], "--world") == 0 && hasValue) {
      const std::string name = argv[++i];
      if (name == "soft-rigid") {
        world = WorldKind::SoftRigid;
      } else if (name == "soft-multibody") {
        world = WorldKind::SoftMultiBody;
      } else if (name == "deformable") {
        world = WorldKind::Deformable;
      } else {
        return usage();
      }
    } else if (std::strcmp(argv[i], "--view") == 0) {
      view = true;
    } else if (std::strcmp(argv[i], "--stock") == 0) {
      stock = true;
    } else if (std::strcmp(argv[i], "--screenshot") == 0 && hasValue) {
      screenshot = argv[++i];
    } else if (std::strcmp(argv[i], "--after") == 0 && hasValue) {
      screenshotSteps = std::atoi(argv[++i]);
    } else {
      return usage();
    }
  }
  if (view || !screenshot.empty()) {
#ifdef THINTOOL_HAVE_VIEWER
    thintool::viewer::BallViewOptions options;
    options.scene.tool = shape;
    options.scene.algorithm = stock ? Algorithm::StockE : Algorithm::ThinTool;
    options.screenshotPath = screenshot;
    options.screenshotSteps = screenshotSteps;
    return thintool::viewer::runBallSceneView(options);
#else
    std::fprintf(stderr, "plate_into_ball: built without the viewer (install libglfw3-dev libgl-dev libimgui-dev "
                         "libstb-dev and reconfigure)\n");
    return 2;
#endif
  }

  const char* worldName = world == WorldKind::SoftMultiBody ? "btSoftMultiBodyDynamicsWorld"
                          : world == WorldKind::Deformable  ? "btDeformableMultiBodyDynamicsWorld"
                                                             : "btSoftRigidDynamicsWorld";
  std::printf("%s into a 128-face soft ball in %s: stock Bullet 3.24 against ThinTool\n\n", toolShapeName(shape),
              worldName);
  std::printf("| algorithm | dt | speed (m/s) | crossed | pierced steps | tool inside | max pen. (mm) | us/step "
              "| tool us/step |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  const Algorithm algorithms[] = {Algorithm::StockA, Algorithm::StockB, Algorithm::StockE, Algorithm::ThinToolPaper,
                                  Algorithm::ThinTool};
  for (Algorithm algorithm : algorithms) {
    for (double rate : rates) {
      for (double speed : speeds) {
        PressSettings settings;
        settings.scene.algorithm = algorithm;
        settings.scene.tool = shape;
        settings.scene.world = world;
        settings.scene.timeStep = 1 / rate;
        settings.speed = speed;
        const PressResult r = runPress(settings);
        const RunMetrics& m = r.metrics;
        char toolTime[32] = "-";
        if (algorithm == Algorithm::ThinTool || algorithm == Algorithm::ThinToolPaper) {
          std::snprintf(toolTime, sizeof toolTime, "%.1f", r.toolMicrosecondsPerStep);
        }
        std::printf("| %s | 1/%g | %g | %d | %d | %s | %.2f | %.1f | %s |\n", algorithmName(algorithm), rate, speed,
                    m.crossed, m.piercedSteps, m.everInside ? "YES" : "no", 1000 * m.maxPenetration,
                    r.microsecondsPerStep, toolTime);
        std::fflush(stdout);
      }
    }
  }
  std::printf("\nJudged by the evaluation suite's ground truth (eval/GroundTruth.h). crossed: nodes that passed\n"
              "through the tool; pierced steps: steps that ended with a soft face deeper than 0.1 mm in the tool;\n"
              "tool inside: the tool's centre was inside the closed membrane after a step (winding number); max pen.:\n"
              "deepest a node or face centroid lay inside the tool after a step. us/step: stepSimulation wall\n"
              "time.\n");
  return 0;
}
