// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// How large a soft ball one world step can afford in real time, stock Bullet against ThinTool.
// The main job's press (examples/plate_into_ball): a kinematic plate 0.8 × 0.02 × 0.8 m moves down
// at 1 m/s from above a settled pressure ball to its mean node height and holds 0.25 s, with stock
// Bullet's variant E (margin 0.05, 10 iterations, SDF voxel 0.02) and with ThinTool's defaults on E's
// soft settings, on balls of 128 faces and up (every fourth size to --max-faces). Each world rate
// has a budget a step: 1000 steps a second (a haptic loop's rate) has 1 ms, 60 has 16.7 ms. For each
// rate it prints every run: the mean and the 99th-percentile step (stepSimulation's wall time, over
// the press and the hold), ThinTool's own share of the mean, and whether the plate kept out (nodes
// through it, the plate's centre inside the ball: the main job's metrics). Then, per algorithm, the
// largest ball whose 99th-percentile step fits the budget. Times depend on the machine; one core.
//
//   realtime [--max-faces 32768] [--rates 1000,60]

#include "SoftBallScene.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

using namespace thintool::scenes;

namespace {

struct Run {
  Algorithm algorithm;
  int faces = 0;
  double meanMicroseconds = 0;
  double p99Microseconds = 0;
  double toolMicroseconds = 0;
  int crossed = 0;
  bool everInside = false;
};

// The step time below which 99 % of the steps fall (the slowest one for fewer than 100 steps).
double percentile99(std::vector<double> times) {
  if (times.empty()) return 0;
  std::sort(times.begin(), times.end());
  const std::size_t index = std::min(times.size() - 1, (times.size() * 99) / 100);
  return times[index];
}

Run press(Algorithm algorithm, int faces, double rate) {
  PressSettings settings;
  settings.scene.algorithm = algorithm;
  settings.scene.ballResolution = faces / 2 - 1;  // CreateEllipsoid's points make 2·(res + 1) faces
  settings.scene.exactBallHull = true;
  settings.scene.timeStep = 1 / rate;
  settings.speed = 1;
  const PressResult result = runPress(settings);
  Run run{algorithm, faces};
  run.meanMicroseconds = result.microsecondsPerStep;
  run.p99Microseconds = percentile99(result.stepMicroseconds);
  run.toolMicroseconds = result.toolMicrosecondsPerStep;
  run.crossed = result.metrics.crossed;
  run.everInside = result.metrics.everInside;
  return run;
}

std::vector<double> parseList(const char* text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(std::atof(item.c_str()));
  return values;
}

int usage() {
  std::fprintf(stderr, "usage: realtime [--max-faces 32768] [--rates 1000,60]\n"
                       "  balls of 128, 512, 2048, ... faces up to --max-faces; --rates lists world steps a second,\n"
                       "  each with a budget of one period a step\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int maxFaces = 32768;
  std::vector<double> rates{1000, 60};
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (std::strcmp(argv[i], "--max-faces") == 0 && hasValue) {
      maxFaces = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--rates") == 0 && hasValue) {
      rates = parseList(argv[++i]);
    } else {
      return usage();
    }
  }
  if (maxFaces < 128 || rates.empty() ||
      std::any_of(rates.begin(), rates.end(), [](double rate) { return !(rate > 0); })) {
    return usage();
  }

  const Algorithm algorithms[] = {Algorithm::StockE, Algorithm::ThinTool};
  for (const double rate : rates) {
    const double budget = 1e6 / rate;
    std::printf("\n%.0f steps a second, %.0f us a step:\n\n", rate, budget);
    std::printf("| algorithm | faces | mean us/step | 99th percentile us/step | ThinTool us/step | crossed | "
                "tool inside |\n|---|---|---|---|---|---|---|\n");
    std::vector<Run> runs;
    for (int faces = 128; faces <= maxFaces; faces *= 4) {
      for (const Algorithm algorithm : algorithms) {
        const Run run = press(algorithm, faces, rate);
        runs.push_back(run);
        char tool[32] = "-";
        if (algorithm == Algorithm::ThinTool) std::snprintf(tool, sizeof tool, "%.1f", run.toolMicroseconds);
        std::printf("| %s | %d | %.1f | %.1f | %s | %d | %s |\n", algorithmName(algorithm), faces, run.meanMicroseconds,
                    run.p99Microseconds, tool, run.crossed, run.everInside ? "YES" : "no");
        std::fflush(stdout);
      }
    }
    std::printf("\nlargest ball whose 99th-percentile step fits %.0f us:\n", budget);
    for (const Algorithm algorithm : algorithms) {
      // The sizes from the smallest up, as long as each fits.
      const Run* largest = nullptr;
      for (const Run& run : runs) {
        if (run.algorithm != algorithm) continue;
        if (run.p99Microseconds > budget) break;
        largest = &run;
      }
      if (largest == nullptr) {
        std::printf("- %s: none of the sizes run\n", algorithmName(algorithm));
      } else {
        std::printf("- %s: %d faces (mean %.1f us, 99th percentile %.1f us)\n", algorithmName(algorithm),
                    largest->faces, largest->meanMicroseconds, largest->p99Microseconds);
      }
    }
  }
  return 0;
}
