// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// thintool_generated: runs random scenes from seeds (SceneGenerator.h) and judges each by the
// ground truth (SceneJudge.h). One line per failing seed, with the command that shows it again,
// then a summary; exit status 1 when any failed. Run it without arguments for its usage.

#include "Runner.h"
#include "SceneFile.h"
#include "SceneGenerator.h"
#include "SceneJudge.h"

#include <thintool/core/Error.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace thintool::eval;

const char* kUsage = R"(usage: thintool_generated [options]

Runs the random scene of each seed and judges it by the ground truth: crossed nodes, the tool
inside the soft body, pierced faces, penetration deeper than 0.1 mm, non-finite nodes, energy.

  --seeds A..B       seeds A to B, both included (repeatable)
  --seed S           one seed (repeatable)
  --seed-file F      seeds from a file, one a line; '#' starts a comment
  --algorithm X      swept (default), discrete, paper, ray-only, stock-A, stock-B or stock-E
  --no-last-word     ThinTool without its last word after Bullet's soft solve (ToolOptions::separation)
  --no-holds         ThinTool without its holds in Bullet's soft solve (BulletSettings::holdInSolver)
  --hold-reach R     the holds reach R skins past the skin along their planes (BulletSettings::holdPlaneReach)
  --no-energy-guard  ThinTool without its energy guard after Bullet's soft solve (ToolOptions::energyGuard)
  --no-force-bound   the energy guard without its bound on the forces of the next step
                     (EnergyGuardSettings::boundForcesNextStep)
  --scan-faces       swept detection reads every soft face instead of walking a face tree
                     (BulletSettings::scanFaces)
  --bullet-node-contacts
                     with --deformable: the tools keep Bullet's own node contacts in its solve,
                     not ThinTool's (BulletSettings::deformableNodeContacts off)
  --follow-arc       swept detection confirms a node's chord on a turning tool's arc
                     (ToolOptions::sweptFollowsArc)
  --frictionless     ThinTool's friction off (FrictionSettings); on by default, with stock
                     Bullet's coefficient: the soft body's kDF times the tool's friction
                     (BulletSettings::frictionFromBodies)
  --soft-multibody   build each scene in btSoftMultiBodyDynamicsWorld (PyBullet's soft world)
                     instead of btSoftRigidDynamicsWorld
  --deformable       build each scene in btDeformableMultiBodyDynamicsWorld: the soft body a
                     mass-spring body (springs tied to its node mass and the step), Bullet's
                     implicit solve and rigid contacts, ThinTool's last word after it
  --bullet-kinds     also draw Bullet's own kinds the scenes otherwise leave out: round tools (a
                     ball, a capsule, a box and a ball), pose-matched bodies (kMT), free cloth
                     dropped on a tool that waits under it, and cloth cut during the run; the rest
                     of each seed's scene is the same as without it
  --within-thickness judge only the scenes in which every tool moved less than its own thickness in
                     every step (the narrowest width of its thinnest piece); the rest run, and are
                     counted apart
  --verbose          print each scene's description and every step's ground truth
  --scenes DIR       where vessel.obj is (default: the source tree's eval/scenes)
)";

#ifndef THINTOOL_EVAL_SCENES
#define THINTOOL_EVAL_SCENES "eval/scenes"
#endif

void addSeedRange(const std::string& text, std::vector<std::uint64_t>& seeds) {
  const std::size_t dots = text.find("..");
  if (dots == std::string::npos) throw thintool::Error("--seeds '" + text + "': expected A..B, such as 1..300");
  const std::uint64_t first = parseSeed(text.substr(0, dots));
  const std::uint64_t last = parseSeed(text.substr(dots + 2));
  if (last < first) throw thintool::Error("--seeds '" + text + "': the last seed is before the first");
  for (std::uint64_t s = first; s <= last; ++s) seeds.push_back(s);
}

// The shortest text that reads back as the same number, for the reproduce line.
std::string formatNumber(double value) {
  char text[32];
  const std::to_chars_result written = std::to_chars(text, text + sizeof text, value);
  return std::string(text, written.ptr);
}

AlgorithmKind parseAlgorithm(const std::string& name) {
  for (AlgorithmKind kind : {AlgorithmKind::Swept, AlgorithmKind::Discrete, AlgorithmKind::Paper, AlgorithmKind::RayOnly,
                             AlgorithmKind::StockA, AlgorithmKind::StockB, AlgorithmKind::StockE}) {
    if (name == algorithmKey(kind)) return kind;
  }
  throw thintool::Error("--algorithm '" + name +
                        "': expected swept, discrete, paper, ray-only, stock-A, stock-B or stock-E");
}

void printSteps(const RunResult& run) {
  std::printf("%6s %9s %9s %7s %12s %7s %12s\n", "step", "t (s)", "crossings", "inside", "depth (mm)", "pierced",
              "node (m/s)");
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const StepSample& s = run.samples[i];
    // "fold": inside by the winding number, through a surface that passes through itself;
    // "-": not judged, a kinematic tool reached a pinned node.
    const char* inside = s.pinnedReached ? "-" : s.toolInside ? "yes" : s.selfIntersecting ? "fold" : "no";
    std::printf("%6zu %9.5f %9d %7s %12.4g %7d %12.4g\n", i + 1, s.time, s.crossings, inside,
                s.maxPenetration * 1000, s.piercedFaces, s.nodeSpeed);
  }
  std::printf("faces %d, nodes %d, crossed nodes %d, inside steps %d (and %d with the surface through itself), "
              "pierced steps %d, deepest %.4g mm, peak node speed %.4g m/s, peak tool speed %.4g m/s\n",
              run.softFaces, run.softNodes, run.truth.crossedNodes, run.truth.toolInsideSteps,
              run.truth.selfIntersectingSteps, run.truth.piercedSteps,
              run.truth.maxPenetration * 1000, run.peakNodeSpeed, run.peakToolSpeed);
  std::printf("fastest node while the body settled, before the tools moved: %.4g m/s\n", run.settleNodeSpeed);
  if (run.truth.pinnedReachedStep > 0) {
    std::printf("a kinematic tool reached a pinned node in step %d: the geometric checks judged the steps before\n",
                run.truth.pinnedReachedStep);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::uint64_t> seeds;
  AlgorithmKind algorithm = AlgorithmKind::Swept;
  bool verbose = false;
  bool lastWord = true;
  bool holds = true;
  std::optional<double> holdReach;
  bool energyGuard = true;
  bool boundForces = true;
  bool scanFaces = false;
  bool bulletNodeContacts = false;
  bool followArc = false;
  bool frictionless = false;
  bool softMultiBody = false;
  bool deformable = false;
  bool withinThickness = false;
  GeneratorOptions generatorOptions;
  std::string sceneFolder = THINTOOL_EVAL_SCENES;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw thintool::Error(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "--seeds") {
        addSeedRange(value(), seeds);
      } else if (arg == "--seed") {
        seeds.push_back(parseSeed(value()));
      } else if (arg == "--seed-file") {
        const std::vector<std::uint64_t> fromFile = readSeedFile(value());
        seeds.insert(seeds.end(), fromFile.begin(), fromFile.end());
      } else if (arg == "--algorithm") {
        algorithm = parseAlgorithm(value());
      } else if (arg == "--no-last-word") {
        lastWord = false;
      } else if (arg == "--no-holds") {
        holds = false;
      } else if (arg == "--hold-reach") {
        const std::string text = value();
        char* end = nullptr;
        holdReach = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !(*holdReach >= 0) || !std::isfinite(*holdReach)) {
          throw thintool::Error("--hold-reach: expected a number >= 0, got '" + text + "'");
        }
      } else if (arg == "--no-energy-guard") {
        energyGuard = false;
      } else if (arg == "--no-force-bound") {
        boundForces = false;
      } else if (arg == "--scan-faces") {
        scanFaces = true;
      } else if (arg == "--bullet-node-contacts") {
        bulletNodeContacts = true;
      } else if (arg == "--follow-arc") {
        followArc = true;
      } else if (arg == "--frictionless") {
        frictionless = true;
      } else if (arg == "--soft-multibody") {
        softMultiBody = true;
      } else if (arg == "--deformable") {
        deformable = true;
      } else if (arg == "--bullet-kinds") {
        generatorOptions.bulletKinds = true;
      } else if (arg == "--within-thickness") {
        withinThickness = true;
      } else if (arg == "--verbose") {
        verbose = true;
      } else if (arg == "--scenes") {
        sceneFolder = value();
      } else if (arg == "--help" || arg == "-h") {
        std::cout << kUsage;
        return 0;
      } else {
        throw thintool::Error("unknown option '" + arg + "'");
      }
    }
  } catch (const thintool::Error& e) {
    std::cerr << "thintool_generated: " << e.what() << "\n" << kUsage;
    return 2;
  }
  if (softMultiBody && deformable) {
    std::cerr << "thintool_generated: --soft-multibody and --deformable each name the world; give one\n";
    return 2;
  }
  if (seeds.empty()) {
    std::cerr << kUsage;
    return 2;
  }

  int failed = 0;
  int crossed = 0, inside = 0, pierced = 0, deep = 0, nonFinite = 0, energy = 0, refused = 0;
  int cutShort = 0;  // judged up to the step a kinematic tool reached a pinned node
  int tooFast = 0;   // with --within-thickness: not judged, a tool moved its thickness or more in a step
  const auto begin = std::chrono::steady_clock::now();
  for (std::uint64_t seed : seeds) {
    Verdict verdict;
    try {
      SceneSpec scene = generateScene(seed, sceneFolder, generatorOptions);
      scene.algorithm = algorithm;
      scene.lastWord = lastWord;
      scene.holds = holds;
      scene.holdPlaneReach = holdReach;
      scene.energyGuard = energyGuard;
      scene.boundForces = boundForces;
      scene.scanFaces = scanFaces;
      scene.deformableNodeContacts = !bulletNodeContacts;
      scene.followArc = followArc;
      if (frictionless) scene.friction = false;
      if (verbose) std::printf("%s\n", describeScene(scene).c_str());
      RunOptions options;
      using thintool::scenes::WorldKind;
      options.world = deformable ? WorldKind::Deformable
                      : softMultiBody ? WorldKind::SoftMultiBody
                                      : WorldKind::SoftRigid;
      if (verbose) {
        options.settled = [](double bottom, double top) {
          std::printf("settled: the soft body spans heights %.4f to %.4f m\n", bottom, top);
        };
      }
      RunResult run;
      verdict = runAndJudge(scene, options, &run);
      if (verbose) printSteps(run);
      if (verbose) std::printf("the farthest step of a tool, over its thickness: %.4g\n", run.peakToolStepOverThickness);
      if (verbose && scene.soft.cut) std::printf("the cut cut %d links\n", run.linksCut);
      if (withinThickness && !(run.peakToolStepOverThickness < 1)) {
        ++tooFast;
        continue;
      }
    } catch (const thintool::Error& e) {
      verdict = refusedVerdict(e.what());
    }
    cutShort += verdict.pinnedReachedStep > 0;
    if (!verdict.failed) continue;
    ++failed;
    crossed += verdict.crossed;
    inside += verdict.inside;
    pierced += verdict.pierced;
    deep += verdict.deep;
    nonFinite += verdict.nonFinite;
    energy += verdict.energy;
    refused += verdict.refused;
    const std::string reach = holdReach.has_value() ? " --hold-reach " + formatNumber(*holdReach) : "";
    std::printf("seed %llu failed: %s; reproduce: %s --seed %llu --algorithm %s%s%s%s%s%s%s%s%s%s%s%s%s%s --verbose\n",
                static_cast<unsigned long long>(seed), joinReasons(verdict).c_str(), argv[0],
                static_cast<unsigned long long>(seed), algorithmKey(algorithm), lastWord ? "" : " --no-last-word",
                holds ? "" : " --no-holds", reach.c_str(), energyGuard ? "" : " --no-energy-guard",
                boundForces ? "" : " --no-force-bound", scanFaces ? " --scan-faces" : "", followArc ? " --follow-arc" : "",
                frictionless ? " --frictionless" : "", softMultiBody ? " --soft-multibody" : "",
                deformable ? " --deformable" : "", bulletNodeContacts ? " --bullet-node-contacts" : "",
                generatorOptions.bulletKinds ? " --bullet-kinds" : "",
                withinThickness ? " --within-thickness" : "");
    std::fflush(stdout);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  const std::string notJudged =
      withinThickness ? "; " + std::to_string(tooFast) + " not judged: a tool moved its thickness or more in a step" : "";
  std::printf("%zu scenes, %d failed (crossed %d, inside %d, pierced %d, deep %d, non-finite %d, energy %d, "
              "refused %d; %d judged up to a pinned node%s), %.1f s\n",
              seeds.size(), failed, crossed, inside, pierced, deep, nonFinite, energy, refused, cutShort,
              notJudged.c_str(), seconds);
  return failed > 0 ? 1 : 0;
}
