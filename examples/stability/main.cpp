// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example runs the stability suite's stiff and extreme cases (scenes/StressCases.h) in the
// paper's scene and prints the table of docs/results/stability.md: each case's outcome, its
// largest penetration and kinetic energy, and its cost per step, from the same run. tests/stability holds every case to
// its expectation; this program only reports.
//
//   stability [--filter TEXT] [--frictionless] [--no-energy-guard]
//     --filter TEXT      runs the cases whose group or name contains TEXT
//     --frictionless     turns ThinTool's friction off in each case's tool (on by default, with
//                        Bullet's coefficient: the ball's kDF times the tool's friction)
//     --no-energy-guard  turns the energy guard off in each case's tool (ToolOptions::energyGuard),
//                        to show what it holds

#include "StressCases.h"

#include <cstdio>
#include <cstring>
#include <string>

using namespace thintool::scenes;

int main(int argc, char** argv) {
  std::string filter;
  bool frictionless = false;
  bool noEnergyGuard = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--filter") == 0 && i + 1 < argc) {
      filter = argv[++i];
    } else if (std::strcmp(argv[i], "--frictionless") == 0) {
      frictionless = true;
    } else if (std::strcmp(argv[i], "--no-energy-guard") == 0) {
      noEnergyGuard = true;
    } else {
      std::fprintf(stderr, "usage: stability [--filter TEXT] [--frictionless] [--no-energy-guard]\n");
      return 2;
    }
  }
  std::printf("| group | case | expected | outcome | crossed | deepest node in the tool (mm) | peak energy (J) | "
              "held energy, 1st half / last quarter (J) | peak force (N) | skipped faces | µs/step |\n");
  std::printf("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  int failures = 0;
  for (StressCase& c : stressCases()) {
    if (!filter.empty() && c.group.find(filter) == std::string::npos && c.name.find(filter) == std::string::npos) {
      continue;
    }
    if (frictionless) c.scene.toolOptions.response.friction.enabled = false;
    if (noEnergyGuard) c.scene.toolOptions.energyGuard.enabled = false;
    const StressOutcome o = runStressCase(c);
    std::string why;
    const bool ok = meets(o, c.expectation, &why);
    failures += !ok;
    const char* outcome = !o.error.empty()   ? "rejected"
                          : !o.finite        ? "NaN"
                          : !o.energyBounded ? "energy grows"
                          : o.metrics.crossed > 0 ? "crossed"
                                                  : "ok";
    if (!o.error.empty()) {
      std::printf("| %s | %s | %s | %s%s: %s | | | | | | | |\n", c.group.c_str(), c.name.c_str(),
                  expectationName(c.expectation), outcome, ok ? "" : " **(fails)**", o.error.c_str());
      continue;
    }
    std::printf("| %s | %s | %s | %s%s | %d | %.1f | %.3g | %.3g / %.3g | %.3g | %ld | %.0f |\n", c.group.c_str(),
                c.name.c_str(), expectationName(c.expectation), outcome, ok ? "" : " **(fails)**", o.metrics.crossed,
                1000 * o.deepestInside, o.peakEnergy, o.holdEnergyFirst, o.holdEnergyLast, o.peakForce,
                o.skippedFaces, o.microsecondsPerStep);
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}
