// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example shows the paper's clamp (§IV.A): two thin jaws close on a soft sphere and on a
// vessel, squeeze, lift them 1 m, hold them 2 s and let go, with friction at the jaws (and, for
// comparison, without it). Headless. It writes the force trace and the paper's Fig. 12 plot, the
// resultant force against time while closing, holding and opening.
//
//   clamp_demo [--out DIR]   writes DIR/clamp_demo_force.csv and, with gnuplot, DIR/clamp_demo_force.png
//   clamp_demo --view [--vessel]             the sphere (or the vessel) grasped, in the viewer
//   clamp_demo --screenshot FILE.png [--vessel]   the grasp at 3.5 s (held up), to a PNG
//   clamp_demo --session [--vessel] [--replay FILE [--real-time] | --falcon FIRMWARE.bin]
//                        [--out DIR | --view | --screenshot F.png]
//       the clamp under a haptic device: the shipped grasp trajectory (or FILE) replayed through
//       the 1 kHz haptic loop in lockstep (--real-time: the loop in its own thread, paced by the
//       clock, as with a device), or a Novint Falcon in real time (where built with
//       libnifalcon); the hand feels the load the jaws carry. Writes DIR/clamp_session_<body>.csv
//       and, with gnuplot, its plot; or shows it in the viewer (a replay then runs in real time),
//       the load fed back as an arrow, or writes its frame at 3.5 s to a PNG.

#include "ClampScene.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include "Plot.h"
#ifdef THINTOOL_HAVE_HAPTICS
#include "ClampSession.h"

#include <thintool/haptics/ReplayDevice.h>
#endif
#ifdef THINTOOL_HAVE_NIFALCON
#include "FalconDevice.h"
#endif
#ifdef THINTOOL_HAVE_VIEWER
#include "Viewer.h"
#endif

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

using namespace thintool;
using namespace thintool::scenes;

namespace {

#ifdef THINTOOL_HAVE_VIEWER
// The viewer over the clamp scene: every step drawn, or, for a screenshot, the step at 3.5 s (the
// body lifted and held by then) written to a PNG. Null where there is no display or OpenGL.
std::unique_ptr<viewer::RunWindow> openClampWindow(const char* title, const std::string& screenshotPath) {
  std::unique_ptr<viewer::RunWindow> window = viewer::RunWindow::open(title, screenshotPath, 3.5);
  if (window) {
    window->camera().target = btVector3(0, 1.2f, 0);
    window->camera().distance = 6;
  }
  return window;
}

// The grasp in the viewer.
int view(ClampBody body, const std::string& screenshotPath) {
  const std::unique_ptr<viewer::RunWindow> window = openClampWindow("ThinTool: clamp", screenshotPath);
  if (!window) return 1;
  ClampRunSettings run;
  run.body = body;
  run.observer = [&](const btSoftRigidDynamicsWorld& world, Clamp& clamp, const ClampSample& sample) {
    viewer::Overlay overlay;
    overlay.tools = {&clamp.jaw(0), &clamp.jaw(1)};
    char line[128];
    std::snprintf(line, sizeof line, "%s, %s: t %.2f s, opening %.2f rad", clampBodyName(body), sample.phase.c_str(),
                  sample.time, sample.opening);
    overlay.panelLines.emplace_back(line);
    std::snprintf(line, sizeof line, "grip %.1f N, body %.2f m up", sample.grip, sample.bodyCentreHeight);
    overlay.panelLines.emplace_back(line);
    return window->show(world, overlay, sample.time);
  };
  runClamp(run);
  return window->finish("clamp_demo");
}
#endif

#ifdef THINTOOL_HAVE_HAPTICS
// The clamp under the hand, replayed: the table's row for the session and its trace.
using SessionObserver = std::function<bool(const btSoftRigidDynamicsWorld&, Clamp&, const ClampSessionSample&,
                                            const haptics::HapticLoop&)>;

// observer, when set, watches every step, and a replay then runs in real time.
int session(ClampBody body, std::string trajectory, const std::string& firmware, const std::string& outDir,
            bool realTime, const SessionObserver& observer = nullptr) {
  if (trajectory.empty()) {
    trajectory = std::string(THINTOOL_CLAMP_TRAJECTORIES) + "/grasp-" + clampBodyName(body) + ".csv";
  }
  ClampSessionSettings settings;
  settings.body = body;
  settings.observer = observer;
  settings.realTime = realTime || static_cast<bool>(observer);
  std::unique_ptr<haptics::Device> device;
  try {
    if (!firmware.empty()) {
#ifdef THINTOOL_HAVE_NIFALCON
      device = examples::openFalcon(0, firmware);
      settings.realTime = true;
      trajectory = device->name();
#else
      std::fprintf(stderr, "clamp_demo: built without libnifalcon; install it and reconfigure to use a Falcon\n");
      return 2;
#endif
    } else {
      device = std::make_unique<haptics::ReplayDevice>(haptics::ReplayDevice::fromFile(trajectory));
    }
  } catch (const Error& error) {
    std::fprintf(stderr, "clamp_demo: %s\n", error.what());
    return 1;
  }
  const ClampSessionResult result = runClampSession(settings, *device);
  if (observer) {
    return result.crossed == 0 && !result.jawEverInside ? 0 : 1;  // watched, not measured
  }
  const std::string name = std::string("clamp_session_") + clampBodyName(body);
  const std::string csv = outDir + "/" + name + ".csv";
  std::ofstream out(csv);
  if (!out) {
    std::fprintf(stderr, "clamp_demo: cannot write %s\n", csv.c_str());
    return 1;
  }
  out << "time,device_x,device_y,device_z,opening,body_centre_height,on_clamp_x,on_clamp_y,on_clamp_z,"
         "device_force_x,device_force_y,device_force_z,body_net_force_y,body_pressure_y\n";
  for (const ClampSessionSample& s : result.trace) {
    out << s.time << ',' << s.device.x << ',' << s.device.y << ',' << s.device.z << ',' << s.opening << ','
        << s.bodyCentreHeight << ',' << s.onClamp.x << ',' << s.onClamp.y << ',' << s.onClamp.z << ','
        << s.deviceForce.x << ',' << s.deviceForce.y << ',' << s.deviceForce.z << ',' << s.bodyNetForce.y << ','
        << s.bodyPressure.y << '\n';
  }
  out.close();
  const haptics::LoopStatistics& loop = result.loop;
  std::printf("%s, %s: %d physics steps at %.0f Hz, %.0f us each; haptic loop (%s): %zu ticks, %.1f Hz, period "
              "p50 %.3f ms, p99 %.3f ms, jitter %.3f ms, read-to-write latency p50 %.1f us, p99 %.1f us, clamped %zu; "
              "crossed nodes %d, jaw inside: %s; rest height %.3f m, weight %.2f N\n",
              clampBodyName(body), trajectory.c_str(), result.steps, 1 / settings.timeStep,
              result.physicsMicrosecondsPerStep, settings.realTime ? "real time, own thread" : "lockstep", loop.ticks,
              loop.rate, loop.periodP50 * 1e3, loop.periodP99 * 1e3, loop.jitter * 1e3, loop.latencyP50 * 1e6,
              loop.latencyP99 * 1e6, loop.clampedTicks, result.crossed,
              result.jawEverInside ? "YES" : "no", result.restCentreHeight, result.bodyWeight);
  const double scale = settings.loop.workspaceScale;
  for (const ClampSessionHold& hold : findHolds(result.trace)) {
    std::printf("device still %.2f-%.2f s: body at %.3f m; the jaws carry %.2f N down, the hand feels %.3f N "
                "(x %.0f = %.2f N), peak to peak %.3f N; momentum balance %.2f N, of it the body's own pressure "
                "%.2f N\n",
                hold.from, hold.to, hold.bodyCentreHeight, -hold.onClamp.y, -hold.deviceForce.y, scale,
                -hold.deviceForce.y * scale, hold.deviceForcePeakToPeak, hold.bodyNetForce.y, hold.bodyPressure.y);
  }
  const std::string script =
      "set terminal pngcairo size 1000,560 font ',11'\n"
      "set output '" + outDir + "/" + name + ".png'\n"
      "set datafile separator ','\nset grid\nset key top right\nset xlabel 'time (s)'\n"
      "set ylabel 'force (N)'\nset y2label 'body centre height (m)'\nset ytics nomirror\nset y2tics\n"
      "set title 'Clamp under the hand (" + std::string(clampBodyName(body)) +
      "): close, lift, hold, open; the hand feels the load the jaws carry'\n"
      "plot '" + csv + "' using 1:(-$8) every ::1 with lines lw 2 title 'load the jaws carry, down (N)', "
      "'' using 1:(-$11*" + std::to_string(scale) + ") every ::1 with lines lw 1 title 'device force x workspace scale, down (N)', "
      "'' using 1:6 every ::1 axes x1y2 with lines lw 1 title 'body centre height (m)'\n";
  std::string whyNot;
  if (examples::runGnuplot(outDir + "/" + name + ".gp", script, whyNot)) {
    std::printf("wrote %s and %s/%s.png\n", csv.c_str(), outDir.c_str(), name.c_str());
  } else {
    std::printf("wrote %s; no plot: %s\n", csv.c_str(), whyNot.c_str());
  }
  return result.crossed == 0 && !result.jawEverInside ? 0 : 1;
}
#endif

#if defined(THINTOOL_HAVE_HAPTICS) && defined(THINTOOL_HAVE_VIEWER)
// A session in the viewer, replayed in real time or on a Falcon: the grasp, the load the hand is
// given as an arrow from between the jaws (0.1 m per newton), the loop's rate and the forces in
// the panel; or the frame at 3.5 s (held up) written to screenshotPath.
int viewSession(ClampBody body, const std::string& trajectory, const std::string& firmware,
                const std::string& screenshotPath) {
  const std::unique_ptr<viewer::RunWindow> window = openClampWindow("ThinTool: clamp under the hand", screenshotPath);
  if (!window) return 1;
  double loopRate = 0;
  int steps = 0;
  const SessionObserver observer = [&](const btSoftRigidDynamicsWorld& world, Clamp& clamp,
                                       const ClampSessionSample& sample, const haptics::HapticLoop& loop) {
    if (steps++ % 30 == 0) loopRate = loop.statistics().rate;  // twice a second: it sorts the loop's records
    viewer::Overlay overlay;
    overlay.tools = {&clamp.jaw(0), &clamp.jaw(1)};
    const btVector3 between =
        (clamp.jawBody(0).getWorldTransform().getOrigin() + clamp.jawBody(1).getWorldTransform().getOrigin()) / 2;
    overlay.arrows.push_back({between, between + toBt(sample.onClamp) * btScalar(0.1)});
    char line[160];
    std::snprintf(line, sizeof line, "%s: t %.2f s, opening %.2f rad, body at %.2f m", clampBodyName(body),
                  sample.time, sample.opening, sample.bodyCentreHeight);
    overlay.panelLines.emplace_back(line);
    std::snprintf(line, sizeof line, "haptic loop %.0f Hz; the hand feels %.3f N, the jaws carry %.2f N",
                  loopRate, length(sample.deviceForce), length(sample.onClamp));
    overlay.panelLines.emplace_back(line);
    return window->show(world, overlay, sample.time);
  };
  const int status = session(body, trajectory, firmware, ".", true, observer);
  return window->finish("clamp_demo") != 0 ? 1 : status;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  std::string outDir = ".";
  std::string screenshot;
  bool viewIt = false;
  bool sessionMode = false;
  bool realTime = false;
  std::string trajectory;
  std::string firmware;
  ClampBody viewedBody = ClampBody::Sphere;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      outDir = argv[++i];
    } else if (std::strcmp(argv[i], "--screenshot") == 0 && i + 1 < argc) {
      screenshot = argv[++i];
    } else if (std::strcmp(argv[i], "--session") == 0) {
      sessionMode = true;
    } else if (std::strcmp(argv[i], "--replay") == 0 && i + 1 < argc) {
      trajectory = argv[++i];
    } else if (std::strcmp(argv[i], "--real-time") == 0) {
      realTime = true;
    } else if (std::strcmp(argv[i], "--falcon") == 0 && i + 1 < argc) {
      firmware = argv[++i];
    } else if (std::strcmp(argv[i], "--view") == 0) {
      viewIt = true;
    } else if (std::strcmp(argv[i], "--vessel") == 0) {
      viewedBody = ClampBody::Vessel;
    } else {
      std::fprintf(stderr,
                   "usage: clamp_demo [--out DIR] | --view [--vessel] | --screenshot FILE.png [--vessel] |\n"
                   "       --session [--vessel] [--replay FILE [--real-time] | --falcon FIRMWARE.bin] [--out DIR | --view |\n"
                   "                 --screenshot FILE.png]\n");
      return 2;
    }
  }
  if (sessionMode || !trajectory.empty() || !firmware.empty()) {
#ifdef THINTOOL_HAVE_HAPTICS
    if (viewIt || !screenshot.empty()) {
#ifdef THINTOOL_HAVE_VIEWER
      return viewSession(viewedBody, trajectory, firmware, screenshot);
#else
      std::fprintf(stderr, "clamp_demo: built without the viewer\n");
      return 2;
#endif
    }
    return session(viewedBody, trajectory, firmware, outDir, realTime);
#else
    std::fprintf(stderr, "clamp_demo: built without the haptic layer\n");
    return 2;
#endif
  }
  if (viewIt || !screenshot.empty()) {
#ifdef THINTOOL_HAVE_VIEWER
    return view(viewedBody, screenshot);
#else
    std::fprintf(stderr, "clamp_demo: built without the viewer\n");
    return 2;
#endif
  }
  const std::string csv = outDir + "/clamp_demo_force.csv";
  std::ofstream out(csv);
  if (!out) {
    std::fprintf(stderr, "clamp_demo: cannot write %s\n", csv.c_str());
    return 1;
  }
  out << "body,friction,time,phase,opening,grip,upper_jaw,lower_jaw,body_net_force_y,body_centre_height,"
         "jaws_on_body_y,body_pressure_y\n";

  std::printf("| body | friction | rest height (m) | held at (m) | after release (m) | crossed | jaw inside | "
              "jaw squeeze, upper / lower (N) | at the hold: jaws / own pressure / momentum balance, vertical (N) | us/step |\n"
              "|---|---|---:|---:|---:|---:|---|---:|---:|---:|\n");
  int problems = 0;
  for (ClampBody body : {ClampBody::Sphere, ClampBody::Vessel}) {
    for (bool friction : {true, false}) {
      ClampRunSettings settings;
      settings.body = body;
      settings.friction = friction;
      const ClampRun run = runClamp(settings);
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %d | %s | %.1f / %.1f | %.2f / %.2f / %.2f | %.0f |\n",
                  clampBodyName(body), friction ? "on" : "off", run.restCentreHeight, run.liftedCentreHeight,
                  run.droppedCentreHeight, run.crossed, run.jawEverInside ? "YES" : "no", run.upperSqueeze,
                  run.lowerSqueeze, run.jawsCarry, run.pressureCarries, run.momentumBalance, run.microsecondsPerStep);
      problems += run.crossed > 0 || run.jawEverInside;
      for (const ClampSample& s : run.samples) {
        out << clampBodyName(body) << ',' << (friction ? 1 : 0) << ',' << s.time << ',' << s.phase << ','
            << s.opening << ',' << s.grip << ',' << length(s.onUpperJaw) << ',' << length(s.onLowerJaw) << ','
            << s.bodyNetForce.y << ',' << s.bodyCentreHeight << ',' << s.onBody.y << ',' << s.bodyPressure.y << '\n';
      }
    }
  }
  out.close();

  // Fig. 12: the grip and the jaws' resultant on the body (its weight while held) against time,
  // with friction; the phases as the paper's: closing, holding (lifted), opening.
  const std::string script =
      "set terminal pngcairo size 1000,640 font ',11'\n"
      "set output '" + outDir + "/clamp_demo_force.png'\n"
      "set datafile separator ','\n"
      "set multiplot layout 2,1 title 'Clamp: closing (0-1.5 s), lifting (2-3 s), holding, opening (5-5.5 s)'\n"
      "set ylabel 'force (N)'\nset grid\nset key top right\n"
      "set title 'sphere, friction on'\n"
      "plot '" + csv + "' using (strcol(1) eq 'sphere' && $2 == 1 ? $3 : 1/0):6 with lines lw 2 title 'grip (each jaw, normal)', "
      "'' using (strcol(1) eq 'sphere' && $2 == 1 ? $3 : 1/0):9 with lines lw 1 title 'resultant on the body, vertical (dp/dt - mg)', "
      "'' using (strcol(1) eq 'sphere' && $2 == 1 ? $3 : 1/0):11 with lines lw 1 title 'the jaws on the body, vertical, as they report it'\n"
      "set title 'vessel, friction on'\nset xlabel 'time (s)'\n"
      "plot '" + csv + "' using (strcol(1) eq 'vessel' && $2 == 1 ? $3 : 1/0):6 with lines lw 2 title 'grip (each jaw, normal)', "
      "'' using (strcol(1) eq 'vessel' && $2 == 1 ? $3 : 1/0):9 with lines lw 1 title 'resultant on the body, vertical (dp/dt - mg)', "
      "'' using (strcol(1) eq 'vessel' && $2 == 1 ? $3 : 1/0):11 with lines lw 1 title 'the jaws on the body, vertical, as they report it'\n"
      "unset multiplot\n";
  std::string whyNot;
  if (examples::runGnuplot(outDir + "/clamp_demo_force.gp", script, whyNot)) {
    std::printf("\nwrote %s and %s/clamp_demo_force.png\n", csv.c_str(), outDir.c_str());
  } else {
    std::printf("\nwrote %s; no plot: %s\n", csv.c_str(), whyNot.c_str());
  }
  return problems == 0 ? 0 : 1;
}
