// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example shows a robot's two-finger gripper, a Featherstone multibody in Bullet's soft
// multibody world (or, with --deformable, its deformable world), closing on a soft tetrahedral cube
// and on a tetrahedral cable, lifting each, holding it and letting it go: stock Bullet's
// soft–multibody contact against ThinTool with each finger link registered as a tool. Headless. One table: whether the body rose with the fingers,
// how far it slipped, nodes through a finger (the evaluation suite's ground truth), the squeeze,
// the load the lift's motor carries against the body's momentum balance, and the time a step.
// Where the viewer is built, --view shows one grasp (the cube, or --cable; ThinTool's, or --stock)
// and --screenshot writes its frame at 4 s, lifted and held, to a PNG.
//
//   gripper_grasp [--deformable [--no-finger-contacts] [--bullet-node-contacts]] [--kdf KDF]
//                 [--dt SECONDS] [--grip NEWTONS] [--view | --screenshot FILE.png] [--cable] [--stock]

#include "GripperScene.h"

#ifdef THINTOOL_HAVE_VIEWER
#include "Viewer.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

using namespace thintool::scenes;

namespace {

#ifdef THINTOOL_HAVE_VIEWER
// One grasp in the viewer: every step drawn, or the step at 4 s (lifted and held) written to
// screenshotPath.
int view(GripperSettings settings, const std::string& screenshotPath) {
  const std::unique_ptr<thintool::viewer::RunWindow> window =
      thintool::viewer::RunWindow::open("ThinTool: gripper", screenshotPath, 4);
  if (!window) return 1;
  window->camera().target = btVector3(0, 0.3f, 0);
  window->camera().distance = 1.4f;
  settings.observer = [&](const btCollisionWorld& world, const btAlignedObjectArray<btSoftBody*>& softBodies,
                          const std::array<thintool::Tool*, 2>& fingers, double time) {
    thintool::viewer::Overlay overlay;
    for (thintool::Tool* finger : fingers) {
      if (finger != nullptr) overlay.tools.push_back(finger);
    }
    char line[96];
    std::snprintf(line, sizeof line, "%s, %s: t %.2f s", graspedBodyName(settings.body),
                  settings.thinTool ? "ThinTool" : "stock Bullet", time);
    overlay.panelLines.emplace_back(line);
    return window->show(thintool::viewer::WorldView(world, softBodies), overlay, time);
  };
  runGripper(settings);
  return window->finish("gripper_grasp");
}
#endif

}  // namespace

int main(int argc, char** argv) {
  GripperSettings base;
  bool viewing = false;
  std::string screenshot;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--dt") == 0 && hasValue) {
      base.timeStep = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--grip") == 0 && hasValue) {
      base.gripForce = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--view") == 0) {
      viewing = true;
    } else if (std::strcmp(argv[i], "--screenshot") == 0 && hasValue) {
      viewing = true;
      screenshot = argv[++i];
    } else if (std::strcmp(argv[i], "--cable") == 0) {
      base.body = GraspedBody::Cable;
    } else if (std::strcmp(argv[i], "--stock") == 0) {
      base.thinTool = false;
    } else if (std::strcmp(argv[i], "--deformable") == 0) {
      base.world = WorldKind::Deformable;
    } else if (std::strcmp(argv[i], "--no-finger-contacts") == 0) {
      base.bulletFingerContacts = false;
    } else if (std::strcmp(argv[i], "--bullet-node-contacts") == 0) {
      base.thinToolNodeContacts = false;
    } else if (std::strcmp(argv[i], "--kdf") == 0 && hasValue) {
      base.bodyFriction = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: gripper_grasp [--deformable [--no-finger-contacts] [--bullet-node-contacts]] "
                           "[--kdf KDF] [--dt SECONDS] [--grip NEWTONS] [--view | --screenshot FILE.png] [--cable] "
                           "[--stock]\n");
      return 2;
    }
  }
  if (!(base.timeStep > 0 && base.timeStep <= 0.1) || !(base.gripForce > 0) || !(base.bodyFriction >= 0)) {
    std::fprintf(stderr, "gripper_grasp: --dt must be in (0, 0.1] s, --grip above 0 N and --kdf at least 0\n");
    return 2;
  }
  if (viewing) {
#ifdef THINTOOL_HAVE_VIEWER
    return view(base, screenshot);
#else
    std::fprintf(stderr, "gripper_grasp: built without the viewer\n");
    return 2;
#endif
  }
  std::printf("| body | Bullet | rise / lift (m) | held part's rise (m) | slip (mm) | after release (m) | crossed | "
              "deepest (mm) | grip (N) | lift motor's load (N) | body's m g + dp/dt (N) | reported (N) | ms a step |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const GraspedBody body : {GraspedBody::Cube, GraspedBody::Cable}) {
    for (const bool thinTool : {false, true}) {
      GripperSettings settings = base;
      settings.body = body;
      settings.thinTool = thinTool;
      const GripperRun run = runGripper(settings);
      char reported[32] = "-";
      if (thinTool) std::snprintf(reported, sizeof reported, "%.2f", run.reportedLoad);
      // A body flung apart has nodes a long way inside a finger: its depth in three digits.
      char deepest[32];
      const double deepestMillimetres = 1000 * run.deepest;
      std::snprintf(deepest, sizeof deepest, deepestMillimetres < 1e6 ? "%.1f" : "%.3g", deepestMillimetres);
      std::printf("| %s | %s | %.3f / %.3f | %.3f | %.1f | %.3f | %d | %s | %.1f | %.2f | %.2f | %s | %.2f |%s\n",
                  graspedBodyName(body), thinTool ? "ThinTool" : "stock", run.rise, run.lift, run.heldRise,
                  1000 * run.slip, run.afterRelease, run.crossed, deepest, run.grip, run.liftLoad, run.bodyLoad,
                  reported, run.wallMilliseconds, run.finite ? "" : " not finite");
    }
  }
  return 0;
}
