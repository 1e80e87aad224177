// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// This example runs the stability suite's stiff and extreme cases (scenes/StressCases.h) in the
// paper's scene and prints the table of docs/results/stability.md: each case's outcome, its
// largest penetration and kinetic energy, and its cost per step, from the same run. tests/stability holds every case to
// its expectation; this program only reports.
//
//   stability [--filter TEXT] [--frictionless] [--no-energy-guard] [--stock]
//     --filter TEXT      runs the cases whose group or name contains TEXT
//     --frictionless     turns ThinTool's friction off in each case's tool (on by default, with
//                        Bullet's coefficient: the ball's kDF times the tool's friction)
//     --no-energy-guard  turns the energy guard off in each case's tool (ToolOptions::energyGuard),
//                        to show what it holds
//     --stock            runs the same cases with stock Bullet instead (stock E's soft settings:
//                        the soft body's margin 5 cm, Bullet's own soft–rigid contact), leaving out
//                        those that vary ThinTool's response or force model; the expectation column
//                        is still ThinTool's, and the program exits 0 whatever stock does

#include "StressCases.h"

#include <cstdio>
#include <cstring>
#include <string>

using namespace thintool::scenes;

int main(int argc, char** argv) {
  std::string filter;
  bool frictionless = false;
  bool noEnergyGuard = false;
  bool stock = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--filter") == 0 && i + 1 < argc) {
      filter = argv[++i];
    } else if (std::strcmp(argv[i], "--frictionless") == 0) {
      frictionless = true;
    } else if (std::strcmp(argv[i], "--no-energy-guard") == 0) {
      noEnergyGuard = true;
    } else if (std::strcmp(argv[i], "--stock") == 0) {
      stock = true;
    } else {
      std::fprintf(stderr, "usage: stability [--filter TEXT] [--frictionless] [--no-energy-guard] [--stock]\n");
      return 2;
    }
  }
  std::printf(stock ? "| group | case | ThinTool is expected | stock E's outcome | crossed"
                    : "| group | case | expected | outcome | crossed");
  std::printf(" | deepest node in the tool (mm) | peak energy (J) | "
              "held energy, 1st half / last quarter (J) | peak force (N) | skipped faces | µs/step |\n");
  std::printf("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  int failures = 0;
  for (StressCase& c : stressCases()) {
    if (!filter.empty() && c.group.find(filter) == std::string::npos && c.name.find(filter) == std::string::npos) {
      continue;
    }
    if (stock) {
      // Stock Bullet has no response or force model to vary, and registers no tool it could refuse:
      // each other case once, its scene alone.
      if (c.scene.algorithm != Algorithm::ThinTool || c.scene.toolOptions.force.enabled ||
          c.expectation == Expectation::Rejected) {
        continue;
      }
      c.scene.algorithm = Algorithm::StockE;
      const std::string response = "default response (projection), ";
      if (c.name.compare(0, response.size(), response) == 0) c.name.erase(0, response.size());
    }
    if (frictionless) c.scene.toolOptions.response.friction.enabled = false;
    if (noEnergyGuard) c.scene.toolOptions.energyGuard.enabled = false;
    const StressOutcome o = runStressCase(c);
    std::string why;
    const bool ok = meets(o, c.expectation, &why);
    failures += !ok && !stock;
    const char* outcome = !o.error.empty()   ? "rejected"
                          : !o.finite        ? "NaN"
                          : !o.energyBounded ? "energy grows"
                          : o.metrics.crossed > 0 ? "crossed"
                          : o.metrics.everInside  ? "tool inside"
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
