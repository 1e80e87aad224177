// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The paper's first scene (scenes/SoftBallScene.h) in the viewer, for the examples' --view and
// --screenshot modes. Interactive, the keyboard moves the tool (no device needed):
//   arrows  move it along x and z        W / S   up and down (0.5 m/s held)
//   right mouse button: drag it horizontally, as seen from the camera
//   space   pause and resume              N       one step while paused
//   T       switch stock Bullet (E), the paper's discrete ThinTool and swept ThinTool on the same
//           scene, the tool where it is
//   R       restart                       Esc     quit
// For a screenshot the tool presses down at 1 m/s for the given steps, then the frame is written.

#include "SoftBallScene.h"

#include <string>

namespace thintool::viewer {

struct BallViewOptions {
  scenes::SceneSettings scene;
  std::string screenshotPath;  ///< empty: interactive
  int screenshotSteps = 60;    ///< steps pressed before the screenshot
};

/// Returns a process exit code: 0, or 1 when the window or the screenshot failed (with a message
/// on stderr).
int runBallSceneView(const BallViewOptions& options);

}  // namespace thintool::viewer
