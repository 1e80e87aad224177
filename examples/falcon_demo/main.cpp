// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The paper's first case study with force feedback: a spatula driven by a haptic device through a
// virtual coupling, pressing the 128-face ball; the device feels the tissue's Hunt–Crossley force.
// Without a Falcon it replays a recorded trajectory, headless, and writes the force trace (CSV)
// and its plot (PNG).
//
//   falcon_demo [--trajectory FILE] [--fast] [--out DIR] [--falcon FIRMWARE.bin] [--no-response]
//               [--friction]
//
// --no-response turns the collision stage's response off (ResponseKind::None): the nodes are put
// back out of the spatula by the last word alone, after Bullet's solve, with no solver holds; to
// compare how steady the force is with and without the response. --friction gives the spatula
// the library's default friction (Bullet's coefficient); the paper's spatula, and the demo's, has
// none.

#include "HapticDemo.h"
#include "Plot.h"

#ifdef THINTOOL_HAVE_NIFALCON
#include "FalconDevice.h"
#endif

#include <thintool/haptics/ReplayDevice.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

using namespace thintool;

namespace {

void writeTrace(const std::string& path, const scenes::HapticDemoResult& result) {
  std::ofstream out(path);
  out << "time,device_x,device_y,device_z,tool_x,tool_y,tool_z,device_force_x,device_force_y,device_force_z,"
         "device_force,contact_force_x,contact_force_y,contact_force_z,contact_force,largest_deformation,contacts\n";
  for (const scenes::HapticSample& s : result.trace) {
    out << s.time << ',' << s.device.x << ',' << s.device.y << ',' << s.device.z << ',' << s.tool.x << ','
        << s.tool.y << ',' << s.tool.z << ',' << s.deviceForce.x << ',' << s.deviceForce.y << ',' << s.deviceForce.z
        << ',' << length(s.deviceForce) << ',' << s.contactForce.x << ',' << s.contactForce.y << ','
        << s.contactForce.z << ',' << length(s.contactForce) << ',' << s.largestDeformation << ',' << s.contacts
        << '\n';
  }
}

std::string plotScript(const std::string& csv, const std::string& png) {
  return "set terminal pngcairo size 1000,560 font 'Sans,11'\n"
         "set output '" + png + "'\n"
         "set datafile separator ','\n"
         "set key top right\n"
         "set grid\n"
         "set xlabel 'time (s)'\n"
         "set ylabel 'device force (N)'\n"
         "set y2label 'tissue force on the spatula (N)'\n"
         "set ytics nomirror\n"
         "set y2tics\n"
         "set title 'Falcon demo: the hand feels the coupling, the tissue pushes with Hunt-Crossley'\n"
         "plot '" + csv + "' using 1:11 every ::1 with lines lw 2 title '|device force| (clamped at 8 N)', \\\n"
         "     '' using 1:15 every ::1 axes x1y2 with lines lw 2 title '|tissue force on the tool|'\n";
}

int usage() {
  std::cerr << "usage: falcon_demo [--trajectory FILE] [--fast] [--out DIR] [--falcon FIRMWARE.bin] [--no-response]"
               " [--friction]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string trajectory = THINTOOL_FALCON_TRAJECTORY;
  std::string outDir = ".";
  std::string firmware;
  bool fast = false;
  bool noResponse = false;
  bool friction = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--trajectory" && i + 1 < argc) {
      trajectory = argv[++i];
    } else if (arg == "--out" && i + 1 < argc) {
      outDir = argv[++i];
    } else if (arg == "--falcon" && i + 1 < argc) {
      firmware = argv[++i];
    } else if (arg == "--fast") {
      fast = true;
    } else if (arg == "--no-response") {
      noResponse = true;
    } else if (arg == "--friction") {
      friction = true;
    } else {
      return usage();
    }
  }

  scenes::HapticDemoSettings settings;
  settings.realTime = !fast;
  if (noResponse) {
    settings.toolOptions.response.kind = ResponseKind::None;
  }
  settings.toolOptions.response.friction.enabled = friction;
  std::unique_ptr<haptics::Device> device;
  try {
    if (!firmware.empty()) {
#ifdef THINTOOL_HAVE_NIFALCON
      device = examples::openFalcon(0, firmware);
      settings.realTime = true;
#else
      std::cerr << "falcon_demo: built without libnifalcon; install it and reconfigure to use a Falcon\n";
      return 2;
#endif
    } else {
      device = std::make_unique<haptics::ReplayDevice>(haptics::ReplayDevice::fromFile(trajectory));
    }
  } catch (const Error& error) {
    std::cerr << "falcon_demo: " << error.what() << '\n';
    return 1;
  }

  const haptics::CouplingCheck check =
      haptics::checkStability(settings.loop.coupling, 1 / settings.loop.rate, device->limits().physicalDamping);
  std::printf("device: %s; coupling K = %.0f N/m, B = %.2f N*s/m (stable needs B > K*T/2 = %.2f: %s)\n",
              device->name().c_str(), settings.loop.coupling.stiffness, settings.loop.coupling.damping,
              check.minimumDamping, check.stable ? "yes" : "NO");

  const scenes::HapticDemoResult result = scenes::runHapticDemo(settings, *device);

  const std::string csv = outDir + "/falcon_demo_force.csv";
  const std::string png = outDir + "/falcon_demo_force.png";
  writeTrace(csv, result);
  double peakDevice = 0;
  double peakTissue = 0;
  for (const scenes::HapticSample& s : result.trace) {
    peakDevice = std::max(peakDevice, length(s.deviceForce));
    peakTissue = std::max(peakTissue, length(s.contactForce));
  }
  const haptics::LoopStatistics& loop = result.loop;
  std::printf("%d physics steps at %.0f Hz, %.1f us each; haptic loop (%s): %zu ticks, %.1f Hz, period p50 %.3f ms, "
              "p99 %.3f ms, jitter %.3f ms, pose-to-force latency p50 %.1f us, p99 %.1f us, clamped ticks %zu\n",
              result.steps, settings.physicsRate, result.physicsMicrosecondsPerStep,
              settings.realTime ? "real time, own thread" : "lockstep, as fast as possible", loop.ticks, loop.rate,
              loop.periodP50 * 1e3, loop.periodP99 * 1e3, loop.jitter * 1e3, loop.latencyP50 * 1e6,
              loop.latencyP99 * 1e6, loop.clampedTicks);
  std::printf("peak device force %.2f N, peak tissue force on the spatula %.3f N; crossed nodes %d, tool ever inside "
              "the ball: %s\n",
              peakDevice, peakTissue, result.metrics.crossed, result.metrics.everInside ? "yes" : "no");
  // Held still in the tissue, the force the hand feels should be steady: its spread over each hold.
  for (const scenes::HapticHold& hold : scenes::findHolds(result.trace)) {
    std::printf("held in the tissue %.2f-%.2f s: device force %.3f N, peak to peak %.3f N (%.1f %%)\n", hold.from,
                hold.to, hold.meanForce, hold.peakToPeak, 100 * hold.variation());
  }
  std::string whyNot;
  if (examples::runGnuplot(outDir + "/falcon_demo_force.gp", plotScript(csv, png), whyNot)) {
    std::printf("wrote %s and %s\n", csv.c_str(), png.c_str());
  } else {
    std::printf("wrote %s; no plot: %s\n", csv.c_str(), whyNot.c_str());
  }
  return 0;
}
