// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example shows a robot's two-finger gripper, a Featherstone multibody in Bullet's soft
// multibody world, closing on a soft tetrahedral cube and on a tetrahedral cable, lifting each,
// holding it and letting it go: stock Bullet's soft–multibody contact against ThinTool with each
// finger link registered as a tool. Headless. One table: whether the body rose with the fingers,
// how far it slipped, nodes through a finger (the evaluation suite's ground truth), the squeeze,
// the load the lift's motor carries against the body's momentum balance, and the time a step.
//
//   gripper_grasp [--dt SECONDS] [--grip NEWTONS]

#include "GripperScene.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace thintool::scenes;

int main(int argc, char** argv) {
  GripperSettings base;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--dt") == 0 && hasValue) {
      base.timeStep = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--grip") == 0 && hasValue) {
      base.gripForce = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: gripper_grasp [--dt SECONDS] [--grip NEWTONS]\n");
      return 2;
    }
  }
  if (!(base.timeStep > 0 && base.timeStep <= 0.1) || !(base.gripForce > 0)) {
    std::fprintf(stderr, "gripper_grasp: --dt must be in (0, 0.1] s and --grip above 0 N\n");
    return 2;
  }
  std::printf("| body | Bullet | rise / lift (m) | slip (mm) | after release (m) | crossed | deepest (mm) | "
              "grip (N) | lift motor's load (N) | body's m g - dp/dt (N) | reported (N) | ms a step |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const GraspedBody body : {GraspedBody::Cube, GraspedBody::Cable}) {
    for (const bool thinTool : {false, true}) {
      GripperSettings settings = base;
      settings.body = body;
      settings.thinTool = thinTool;
      const GripperRun run = runGripper(settings);
      char reported[32] = "-";
      if (thinTool) std::snprintf(reported, sizeof reported, "%.2f", run.reportedLoad);
      std::printf("| %s | %s | %.3f / %.3f | %.1f | %.3f | %d | %.1f | %.1f | %.2f | %.2f | %s | %.2f |%s\n",
                  graspedBodyName(body), thinTool ? "ThinTool" : "stock", run.rise, run.lift, 1000 * run.slip,
                  run.afterRelease, run.crossed, 1000 * run.deepest, run.grip, run.liftLoad, run.bodyLoad, reported,
                  run.wallMilliseconds, run.finite ? "" : " not finite");
    }
  }
  return 0;
}
