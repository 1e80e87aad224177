// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "BallSceneView.h"

#include "Viewer.h"

#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <GLFW/glfw3.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

namespace thintool::viewer {

namespace {

constexpr double kStartClearance = 0.15;  // m above the ball's top where the tool starts

struct Session {
  std::unique_ptr<scenes::SoftBallScene> scene;
  btTransform pose;
  double lastStepMicroseconds = 0;
  int steps = 0;
};

void start(Session& session, const scenes::SceneSettings& settings, const btTransform* keepPose) {
  session.scene = std::make_unique<scenes::SoftBallScene>(settings);
  session.scene->settle();
  session.pose = keepPose != nullptr
                     ? *keepPose
                     : btTransform(btQuaternion::getIdentity(), session.scene->aboveBall(session.scene->ballTop() +
                                                                                          kStartClearance));
  session.steps = 0;
}

Overlay overlayOf(Session& session, bool paused) {
  Overlay overlay;
  scenes::SoftBallScene& scene = *session.scene;
  char line[160];
  std::snprintf(line, sizeof line, "%s, %s%s", scenes::algorithmName(scene.settings().algorithm),
                scenes::toolShapeName(scene.settings().tool), paused ? "  [paused]" : "");
  overlay.panelLines.emplace_back(line);
  std::snprintf(line, sizeof line, "step %d, dt 1/%.0f s, %.0f us", session.steps, 1 / scene.settings().timeStep,
                session.lastStepMicroseconds);
  overlay.panelLines.emplace_back(line);
  if (Tool* tool = scene.tool()) {
    overlay.tools.push_back(tool);
    const ToolStepReport& report = tool->report();
    const DetectionCounters& d = report.diagnostics.detection;
    std::snprintf(line, sizeof line, "contacts %zu, colliding nodes %u, excluded: check 1 %u, check 2 %u",
                  report.contacts.size(), unsigned(d.colliding), unsigned(d.excludedByCheck1),
                  unsigned(d.excludedByCheck2));
    overlay.panelLines.emplace_back(line);
    std::snprintf(line, sizeof line, "force on the tool %.2f N (response), ThinTool %.0f us",
                  length(report.wrench.force),
                  report.diagnostics.detectionMicroseconds + report.diagnostics.responseMicroseconds +
                      report.diagnostics.lastWord.microseconds);
    overlay.panelLines.emplace_back(line);
  } else {
    overlay.panelLines.emplace_back("stock Bullet: no ThinTool report");
  }
  overlay.panelLines.emplace_back("nodes: red colliding, orange excluded by check 1, violet by check 2");
  overlay.panelLines.emplace_back("drag: turn, scroll: zoom, right-drag/arrows/W/S: tool, space: pause, N: step, "
                                  "T: switch");
  return overlay;
}

}  // namespace

int runBallSceneView(const BallViewOptions& options) {
  ViewerSettings settings;
  settings.visible = options.screenshotPath.empty();
  settings.title = "ThinTool: plate into ball";
  std::unique_ptr<Viewer> viewer;
  try {
    viewer = std::make_unique<Viewer>(settings);
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  scenes::SceneSettings sceneSettings = options.scene;
  Session session;
  start(session, sceneSettings, nullptr);
  viewer->camera().target = session.scene->aboveBall(1);
  const double dt = sceneSettings.timeStep;

  if (!options.screenshotPath.empty()) {
    for (int i = 0; i < options.screenshotSteps; ++i) {
      session.pose.setOrigin(session.pose.getOrigin() - btVector3(0, btScalar(1.0 * dt), 0));
      session.lastStepMicroseconds = session.scene->step(session.pose);
      ++session.steps;
    }
    if (!viewer->renderToFile(session.scene->world(), overlayOf(session, false), options.screenshotPath)) {
      std::fprintf(stderr, "viewer: cannot write %s\n", options.screenshotPath.c_str());
      return 1;
    }
    std::printf("wrote %s\n", options.screenshotPath.c_str());
    return 0;
  }

  bool paused = false;
  bool running = true;
  while (running) {
    bool stepOnce = false;
    for (int key : viewer->keysPressed()) {
      if (key == GLFW_KEY_ESCAPE) running = false;
      if (key == GLFW_KEY_SPACE) paused = !paused;
      if (key == GLFW_KEY_N) stepOnce = true;
      if (key == GLFW_KEY_R) start(session, sceneSettings, nullptr);
      if (key == GLFW_KEY_T) {
        // Stock Bullet (E), the paper's discrete ThinTool (whose checks exclude nodes), swept ThinTool.
        const scenes::Algorithm current = sceneSettings.algorithm;
        sceneSettings.algorithm = current == scenes::Algorithm::StockE          ? scenes::Algorithm::ThinToolPaper
                                  : current == scenes::Algorithm::ThinToolPaper ? scenes::Algorithm::ThinTool
                                                                                : scenes::Algorithm::StockE;
        const btTransform keep = session.pose;
        start(session, sceneSettings, &keep);
      }
    }
    const btScalar move = btScalar(0.5 * dt);
    btVector3 delta(0, 0, 0);
    if (viewer->keyDown(GLFW_KEY_LEFT)) delta.setX(-move);
    if (viewer->keyDown(GLFW_KEY_RIGHT)) delta.setX(move);
    if (viewer->keyDown(GLFW_KEY_UP)) delta.setZ(-move);
    if (viewer->keyDown(GLFW_KEY_DOWN)) delta.setZ(move);
    if (viewer->keyDown(GLFW_KEY_W)) delta.setY(move);
    if (viewer->keyDown(GLFW_KEY_S)) delta.setY(-move);
    session.pose.setOrigin(session.pose.getOrigin() + delta + viewer->takeRightDrag(0.005f));
    if (!paused || stepOnce) {
      session.lastStepMicroseconds = session.scene->step(session.pose);
      ++session.steps;
    }
    running = viewer->frame(session.scene->world(), overlayOf(session, paused)) && running;
  }
  return 0;
}

}  // namespace thintool::viewer
