// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The whole of btSoftRigidDynamicsWorld::stepSimulation, stock Bullet (baseline.md's variant E)
// against ThinTool's defaults, and against ThinTool scanning the faces (BulletSettings::scanFaces),
// on HandlerBench.cpp's scene: the plate pressing a soft ball of 128 to 65,536 faces with a 50 mm
// margin, without gravity and pressure. HandlerBench times one stage; what a program pays is the
// step, which also holds the costs a stage's clock cannot see: the soft solve (ThinTool's copy of
// Bullet's, with its last word), and Bullet's upkeep of structures the stage asks for
// (predictMotion refits the soft body's face tree in every step once ThinTool's gather has built
// it; stock Bullet builds none for this ball, nor does ThinTool when it scans).
//
// Each iteration builds the scene (untimed), brings the plate down at 1 m/s from clear of the
// margin until its underside is a depth below the ball's top (the second argument, mm: 5 mm as
// HandlerBench's last step, 30 mm pressed in), and holds it there for half a second; the steps
// from the first in which the plate is within the margin to the end are timed one by one, and the
// iteration's time is their mean. stageUs and lastWordUs are ThinTool's own clocks over the same
// steps (Tool::report: detection and response; the last word, with the pass over the nodes that it
// shares with Bullet's velocity update, which sharedPassUs times on its own). pairsUs is the time
// of the ball's pairs in Bullet's dispatcher, the same clock for both algorithms (a timing near
// callback): what HandlerBench replays, here in the run, so that stock's handler and ThinTool's
// collision stage plus its last word come from the same steps. scripts/step-table.py runs them and
// prints the real-time and the cost tables of docs/results/evaluation.md.
//
// Deviations from a run: no gravity or pressure (as HandlerBench, so that no settling is needed at
// 65,536 faces), a kinematic plate.

#include "FloatingBall.h"

#include <SoftBallScene.h>

#include <thintool/thintool.h>

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>

namespace thintool::scenes {
namespace {

constexpr double kTimeStep = 1.0 / 60;
constexpr double kSpeed = 1;         // m/s: 16.7 mm a step
constexpr double kMargin = 0.05;     // m: the ball's margin, ThinTool's skin
constexpr double kClearance = 0.08;  // m: the underside above the top at the start
constexpr int kHoldSteps = 30;     // half a second

// Times the dispatcher's pairs that hold one body, for both algorithms alike. Bullet's near
// callback is a plain function: the clock it reads is the one installed.
struct PairClock {
  const btCollisionObject* body = nullptr;
  btNearCallback inner = nullptr;
  double seconds = 0;
};
PairClock* installedClock = nullptr;

void timedNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
  PairClock& clock = *installedClock;
  const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
  if (a != clock.body && b != clock.body) {
    clock.inner(pair, dispatcher, info);
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  clock.inner(pair, dispatcher, info);
  clock.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void installPairClock(SoftBallScene& scene, PairClock& clock) {
  auto& dispatcher = *static_cast<btCollisionDispatcher*>(scene.dynamicsWorld().getDispatcher());
  clock.body = &scene.ball();
  clock.inner = dispatcher.getNearCallback();
  installedClock = &clock;
  dispatcher.setNearCallback(timedNearCallback);
}

void run(benchmark::State& state, Algorithm algorithm, bool scanFaces = false, WorldKind world = WorldKind::SoftRigid) {
  const int faces = static_cast<int>(state.range(0));
  const double depth = 0.001 * static_cast<double>(state.range(1));  // m
  double stepSum = 0;
  double stageSum = 0;
  double lastWordSum = 0;
  double sharedPassSum = 0;
  double pairsSum = 0;
  // The second half of the hold alone: the cost once each algorithm has what it builds as it goes
  // (stock's distance-field cells, ThinTool's face tree and memory).
  double heldPairsSum = 0;
  double heldLastWordSum = 0;
  int held = 0;
  int timed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    ToolOptions options;
    options.bullet.scanFaces = scanFaces;
    const std::unique_ptr<SoftBallScene> floating = makeFloatingBall(algorithm, faces, kMargin, kTimeStep, options, world);
    SoftBallScene& scene = *floating;
    if (scene.ball().m_faces.size() != faces) {
      state.SkipWithError("the ball does not have the faces asked for");
      return;
    }
    const double halfThickness = scene.toolBox().halfExtents.y;
    const double top = scene.ballTop();
    if (Tool* tool = scene.tool()) tool->resetMotion();  // from where the tool was parked: a jump
    PairClock pairClock;
    installPairClock(scene, pairClock);
    double iterationSeconds = 0;
    int iterationSteps = 0;
    double underside = top + kClearance;
    for (int hold = 0; hold < kHoldSteps;) {
      underside = std::max(underside - kSpeed * kTimeStep, top - depth);
      if (underside <= top - depth) ++hold;
      pairClock.seconds = 0;
      const double microseconds = scene.step(btTransform(btQuaternion::getIdentity(),
                                                         scene.aboveBall(underside + halfThickness)));
      if (underside > top + kMargin) continue;  // not yet within the margin: untimed
      iterationSeconds += microseconds * 1e-6;
      pairsSum += pairClock.seconds * 1e6;
      ++iterationSteps;
      const bool steady = hold > kHoldSteps / 2;
      if (steady) {
        heldPairsSum += pairClock.seconds * 1e6;
        ++held;
      }
      if (Tool* tool = scene.tool()) {
        const ToolDiagnostics& d = tool->report().diagnostics;
        stageSum += d.detectionMicroseconds + d.responseMicroseconds;
        lastWordSum += d.lastWord.microseconds;
        sharedPassSum += d.lastWord.sharedPassMicroseconds;
        if (steady) heldLastWordSum += d.lastWord.microseconds;
      }
    }
    stepSum += iterationSeconds * 1e6;
    timed += iterationSteps;
    state.SetIterationTime(iterationSeconds / iterationSteps);
    state.ResumeTiming();
  }
  if (timed == 0) return;
  state.counters["softFaces"] = faces;
  state.counters["stepsTimed"] = timed;
  state.counters["stepUs"] = stepSum / timed;
  state.counters["pairsUs"] = pairsSum / timed;
  state.counters["heldPairsUs"] = heldPairsSum / held;
  if (algorithm != Algorithm::StockE) {
    state.counters["stageUs"] = stageSum / timed;
    state.counters["lastWordUs"] = lastWordSum / timed;
    state.counters["sharedPassUs"] = sharedPassSum / timed;
    state.counters["heldLastWordUs"] = heldLastWordSum / held;
  }
}

void StockStep(benchmark::State& state) { run(state, Algorithm::StockE); }
void ThinToolStep(benchmark::State& state) { run(state, Algorithm::ThinTool); }
void ThinToolScanStep(benchmark::State& state) { run(state, Algorithm::ThinTool, true); }

// Arguments: the ball's faces, and the depth the plate holds at (mm). One iteration each: the
// table's script asks for repetitions (scripts/step-table.py).
#define THINTOOL_STEP_SIZES                                                                         \
  ->ArgsProduct({{128, 1024, 4096, 16384, 65536}, {5, 30}})->UseManualTime()->Iterations(1) \
      ->Unit(benchmark::kMicrosecond)
BENCHMARK(StockStep)->Name("WholeStep/Stock") THINTOOL_STEP_SIZES;
BENCHMARK(ThinToolStep)->Name("WholeStep/ThinTool") THINTOOL_STEP_SIZES;
BENCHMARK(ThinToolScanStep)->Name("WholeStep/ThinToolScan") THINTOOL_STEP_SIZES;

// Bullet's deformable world (a mass-spring ball, scenes::WorldKind::Deformable): the pairs are
// Bullet's for both, and ThinTool's part of the step is its last word. Its implicit solve makes
// the larger balls' steps long; three sizes.
void StockDeformableStep(benchmark::State& state) { run(state, Algorithm::StockE, false, WorldKind::Deformable); }
void ThinToolDeformableStep(benchmark::State& state) { run(state, Algorithm::ThinTool, false, WorldKind::Deformable); }
#define THINTOOL_DEFORMABLE_STEP_SIZES                                                  \
  ->ArgsProduct({{128, 1024, 4096}, {5, 30}})->UseManualTime()->Iterations(1) \
      ->Unit(benchmark::kMicrosecond)
BENCHMARK(StockDeformableStep)->Name("WholeStepDeformable/Stock") THINTOOL_DEFORMABLE_STEP_SIZES;
BENCHMARK(ThinToolDeformableStep)->Name("WholeStepDeformable/ThinTool") THINTOOL_DEFORMABLE_STEP_SIZES;

}  // namespace
}  // namespace thintool::scenes
