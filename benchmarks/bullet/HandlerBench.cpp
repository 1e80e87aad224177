// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// Stock Bullet's soft–rigid collision handler and ThinTool's on the same scene, in the same run:
// scenes/SoftBallScene's plate (0.8 × 0.02 × 0.8 m, 576 ThinTool sample nodes) pressing a soft
// ball of radius 1 made of btSoftBodyHelpers::CreateEllipsoid's points, 128 to 65,536 triangles,
// with stock E's soft settings (margin 0.05, SDF voxel 0.02) for both, and with a 5 mm margin.
// CreateEllipsoid itself cannot make the large balls (its hull library stops near 2,360 faces), so
// the scene joins the same points by SceneSettings::exactBallHull. The ball floats, without gravity
// and pressure, so that it keeps the shape it was built with until the plate arrives (no settling,
// which would take seconds at 65k faces), and the plate comes down at 1 m/s in steps of 1/60 s,
// from clear of the soft margin until its underside is 5 mm below the ball's top, each algorithm
// answering the contact as in a run. With the 5 mm margin the last step is the first contact, so
// both algorithms see the same ball; with 50 mm each has answered three steps of contact before.
//
// What is timed is the collision stage of the last of those steps for the tool's pairs with the
// ball: what Bullet's dispatcher runs for them, through its near callback. For stock Bullet that is
// btSoftRigidCollisionAlgorithm::processCollision, i.e. btSoftBody::defaultCollisionHandler (its
// nodes against the plate's sparse distance field; the solver uses the contacts later). For
// ThinTool it is its algorithm's processCollision for the tool's pairs (the swept proxy's, and the
// tool body's own, which is idle): gather, detection, response and the solver holds, since in
// ThinTool the response is part of the collision stage. ThinTool's last word runs later in the
// step, after Bullet's soft solve, and is not replayed: lastWordUs is its time in the real step
// (one sample, with cold caches), sharedPassUs the part of it spent in the pass over the nodes that
// it shares with Bullet's velocity update, which a stock step makes too, and guardUs the part spent
// in the energy guard's passes over the ball's nodes before Bullet's solve and after the last word.
// The detectUs and
// responseUs counters are ThinTool's own clock for its two parts (Tool::report), a cross-check of
// the measured time, and detectUs alone is the detection stage.
//
// The stage is replayed, not stepped: the ball's nodes are captured when the dispatcher reaches the
// tool's pairs in that step, and each iteration restores them near the tool (untimed) and runs the
// pairs again. Stock's handler only appends contacts (cleared each iteration); ThinTool's moves
// nodes (restored) and keeps memory from step to step (where it last left each node, which side it
// came from), which the replay does not rewind: from the first replay on, each call sweeps the
// nodes from where the previous call left them to their predicted positions, as in a run where the
// solver moves nothing in between. Each replay also begins ThinTool's record of the collision pass
// again (src/bullet/CollisionPass.h), as Bullet's box update does in a step. The contacts counter
// is the replay's (stepContacts the real step's), and stepUs is the real step's time for the same
// pairs (stepDetectUs and stepFacesNear ThinTool's detection in it), where stock builds distance
// field cells that the replays find built. facesNear is what ThinTool gathered (facesWalked the
// faces whose face-tree leaves its walk met), facesInSweptBox the faces that meet the plate's swept
// box grown by the margin, nodesNear the nodes in stock's query box. The allocs counter counts
// operator new and Bullet's allocator per replay.
//
// The rows whose names end in SoftMultiBody build the same scene in btSoftMultiBodyDynamicsWorld
// (with btMultiBodyConstraintSolver), PyBullet's soft world, where Bullet collides the pairs the
// same way: each world's stage against stock's in it. Those ending in Deformable build it in
// btDeformableMultiBodyDynamicsWorld, the ball a mass-spring body, where the tool's pairs are
// Bullet's own for both (its deformable node and face contacts, counted in contacts): ThinTool's
// part is its last word, lastWordUs, after Bullet's solve.
//
// Deviations from a run: no gravity or pressure, and the caches are warm (the replay revisits the
// same data).

#include "../../src/bullet/CollisionPass.h"

#include "FloatingBall.h"

#include <CountingAllocator.h>
#include <SoftBallScene.h>

#include <thintool/thintool.h>

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <LinearMath/btAlignedAllocator.h>
#include <btBulletDynamicsCommon.h>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <tuple>
#include <memory>
#include <utility>
#include <vector>

namespace thintool::scenes {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kTimeStep = 1.0 / 60;
constexpr double kSpeed = 1;              // m/s: 16.7 mm a step
constexpr double kFinalDepth = 0.005;     // m: the underside below the ball's top at the end
constexpr int kPressSteps = 4;            // the first starts 62 mm above the top, beyond the 50 mm margin
constexpr double kRestoreReach = 0.3;     // m around the plate's swept box: nodes restored each replay

// The collision stage of the last press step, captured by the dispatcher's near callback. Bullet's
// callback is a plain function, so the capture in progress is reached through this pointer.
struct Replay;
Replay* capturing = nullptr;

struct Replay {
  std::unique_ptr<SoftBallScene> scene;
  std::vector<btBroadphasePair*> pairs;  // the ball's pairs with the tool (and ThinTool's proxy)
  std::vector<btVector3> x, q, v;        // every node at the collision stage
  std::vector<int> nearNodes;            // restored before each replay
  double stepMicroseconds = 0;
  double stepLastWordMicroseconds = 0;  // ThinTool's last word in that step (after Bullet's soft solve)
  double stepSharedPassMicroseconds = 0;  // of it, the pass over the nodes shared with Bullet's own
  double stepGuardMicroseconds = 0;       // of it, the energy guard's passes
  long stepContacts = 0;
  double stepDetectMicroseconds = 0;  // ThinTool's own clock in the real step
  double stepFacesNear = 0;
  int nodesNear = 0;         // nodes inside the stock handler's query box
  int facesInSweptBox = 0;   // faces meeting the plate's swept box grown by the margin

  static void nearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
    Replay& self = *capturing;
    const btSoftBody* ball = &self.scene->ball();
    const void* ground = &self.scene->ground();
    const void* a = pair.m_pProxy0->m_clientObject;
    const void* b = pair.m_pProxy1->m_clientObject;
    // The ball's pairs but its pair with the ground (which exists, though the two do not touch).
    const bool withBall = (a == ball || b == ball) && a != ground && b != ground;
    if (withBall && self.pairs.empty()) {
      const int n = ball->m_nodes.size();
      self.x.resize(n);
      self.q.resize(n);
      self.v.resize(n);
      for (int i = 0; i < n; ++i) {
        self.x[i] = ball->m_nodes[i].m_x;
        self.q[i] = ball->m_nodes[i].m_q;
        self.v[i] = ball->m_nodes[i].m_v;
      }
    }
    const auto start = Clock::now();
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
    if (withBall) {
      self.stepMicroseconds += std::chrono::duration<double, std::micro>(Clock::now() - start).count();
      self.pairs.push_back(&pair);
    }
  }

  Replay(Algorithm algorithm, int faces, double margin, WorldKind softWorld) {
    scene = makeFloatingBall(algorithm, faces, margin, kTimeStep, {}, softWorld);
    btDiscreteDynamicsWorld& world = scene->dynamicsWorld();
    const double halfThickness = scene->toolBox().halfExtents.y;
    const double finalHeight = scene->ballTop() - kFinalDepth + halfThickness;
    const double stepLength = kSpeed * kTimeStep;
    auto poseAt = [&](int step) {
      return btTransform(btQuaternion::getIdentity(), scene->aboveBall(finalHeight + (kPressSteps - step) * stepLength));
    };
    if (thintool::Tool* tool = scene->tool()) {
      tool->resetMotion();  // from where the tool was parked: a jump, not a sweep
    }
    scene->step(poseAt(0));
    for (int step = 1; step < kPressSteps; ++step) {
      scene->step(poseAt(step));
    }
    auto* dispatcher = static_cast<btCollisionDispatcher*>(world.getDispatcher());
    capturing = this;
    dispatcher->setNearCallback(&Replay::nearCallback);
    scene->step(poseAt(kPressSteps));
    dispatcher->setNearCallback(&btCollisionDispatcher::defaultNearCallback);
    capturing = nullptr;
    thintool::Tool* tool = scene->tool();
    if (tool != nullptr) {
      const thintool::ToolDiagnostics& d = tool->report().diagnostics;
      stepLastWordMicroseconds = d.lastWord.microseconds;
      stepSharedPassMicroseconds = d.lastWord.sharedPassMicroseconds;
      stepGuardMicroseconds = d.lastWord.energyGuardMicroseconds;
    }
    if (tool != nullptr && softWorld != WorldKind::Deformable) {
      const thintool::ToolDiagnostics& d = tool->report().diagnostics;
      stepContacts = static_cast<long>(d.detection.colliding);
      stepDetectMicroseconds = d.detectionMicroseconds;
      stepFacesNear = d.detection.facesGathered;
    } else {
      stepContacts = countStockContacts();
    }

    // Back to the collision stage. The trees' volumes still are those of that step's prediction.
    btSoftBody& ball = scene->ball();
    for (int i = 0; i < ball.m_nodes.size(); ++i) {
      ball.m_nodes[i].m_x = x[i];
      ball.m_nodes[i].m_q = q[i];
      ball.m_nodes[i].m_v = v[i];
    }
    clearContacts();

    btVector3 boxMin, boxMax, lastMin, lastMax;
    btCollisionShape& toolShape = *scene->toolBody().getCollisionShape();
    toolShape.getAabb(poseAt(kPressSteps - 1), boxMin, boxMax);
    toolShape.getAabb(poseAt(kPressSteps), lastMin, lastMax);
    boxMin.setMin(lastMin);
    boxMax.setMax(lastMax);
    const btVector3 reach(kRestoreReach, kRestoreReach, kRestoreReach);
    const btVector3 stockReach = btVector3(1, 1, 1) * btScalar(margin);
    for (int i = 0; i < ball.m_nodes.size(); ++i) {
      const btVector3& p = x[i];
      if (p.x() >= boxMin.x() - reach.x() && p.y() >= boxMin.y() - reach.y() && p.z() >= boxMin.z() - reach.z() &&
          p.x() <= boxMax.x() + reach.x() && p.y() <= boxMax.y() + reach.y() && p.z() <= boxMax.z() + reach.z()) {
        nearNodes.push_back(i);
      }
      const btVector3 lo = lastMin - stockReach;
      const btVector3 hi = lastMax + stockReach;
      if (p.x() >= lo.x() && p.y() >= lo.y() && p.z() >= lo.z() && p.x() <= hi.x() && p.y() <= hi.y() &&
          p.z() <= hi.z()) {
        ++nodesNear;
      }
    }
    const btVector3 sweptMin = boxMin - stockReach;
    const btVector3 sweptMax = boxMax + stockReach;
    for (int f = 0; f < ball.m_faces.size(); ++f) {
      btVector3 faceMin = ball.m_faces[f].m_n[0]->m_x;
      btVector3 faceMax = faceMin;
      for (int k = 1; k < 3; ++k) {
        faceMin.setMin(ball.m_faces[f].m_n[k]->m_x);
        faceMax.setMax(ball.m_faces[f].m_n[k]->m_x);
      }
      if (faceMin.x() <= sweptMax.x() && faceMin.y() <= sweptMax.y() && faceMin.z() <= sweptMax.z() &&
          faceMax.x() >= sweptMin.x() && faceMax.y() >= sweptMin.y() && faceMax.z() >= sweptMin.z()) {
        ++facesInSweptBox;
      }
    }
  }

  // Bullet's contacts with the tool: the classic worlds' node contacts, the deformable world's node
  // and face contacts.
  long countStockContacts() const {
    const btSoftBody& ball = scene->ball();
    const auto count = [&](const auto& contacts) {
      long withTool = 0;
      for (int i = 0; i < contacts.size(); ++i) withTool += contacts[i].m_cti.m_colObj == &scene->toolBody() ? 1 : 0;
      return withTool;
    };
    return count(ball.m_rcontacts) + count(ball.m_nodeRigidContacts) + count(ball.m_faceRigidContacts);
  }

  // Empties the ball's contact array and keeps its memory, as Bullet's predictMotion does (whose
  // resize(0) copies an uninitialised RContact, which GCC warns of when it is inlined here).
  void clearContacts() {
    btSoftBody& ball = scene->ball();
    while (ball.m_rcontacts.size() > 0) {
      ball.m_rcontacts.pop_back();
    }
    while (ball.m_nodeRigidContacts.size() > 0) {
      ball.m_nodeRigidContacts.pop_back();
    }
    while (ball.m_faceRigidContacts.size() > 0) {
      ball.m_faceRigidContacts.pop_back();
    }
  }

  void restore() {
    btSoftBody& ball = scene->ball();
    for (int i : nearNodes) {
      ball.m_nodes[i].m_x = x[i];
    }
    clearContacts();
    if (scene->tool() != nullptr) {
      // The nodes are back where the face tree was fitted around them: as far as ThinTool's record
      // of the pass goes, the pass begins again (CollisionPass).
      detail::beginCollisionPass(scene->dynamicsWorld());
    }
  }

  // Runs the pairs as the dispatcher does; returns the wall time (s).
  double runPairs() {
    btDiscreteDynamicsWorld& world = scene->dynamicsWorld();
    auto& dispatcher = *static_cast<btCollisionDispatcher*>(world.getDispatcher());
    const btDispatcherInfo& info = world.getDispatchInfo();
    const btNearCallback callback = dispatcher.getNearCallback();
    const auto start = Clock::now();
    for (btBroadphasePair* pair : pairs) {
      callback(*pair, dispatcher, info);
    }
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  // Whether any node the replay does not restore was moved.
  bool movedFarNodes() const {
    const btSoftBody& ball = scene->ball();
    std::vector<char> restored(x.size(), 0);
    for (int i : nearNodes) {
      restored[static_cast<std::size_t>(i)] = 1;
    }
    for (int i = 0; i < ball.m_nodes.size(); ++i) {
      if (restored[static_cast<std::size_t>(i)] == 0 && ball.m_nodes[i].m_x != x[i]) {
        return true;
      }
    }
    return false;
  }
};

// Built once per process: a 65k-face scene takes seconds, and the benchmark function runs several
// times for each row. Every replay starts from the captured stage, so reuse changes nothing.
Replay& replayFor(Algorithm algorithm, int faces, int marginMillimetres, WorldKind world) {
  static std::map<std::tuple<Algorithm, int, int, WorldKind>, std::unique_ptr<Replay>> replays;
  std::unique_ptr<Replay>& replay = replays[{algorithm, faces, marginMillimetres, world}];
  if (replay == nullptr) {
    test::installCountingBulletAllocator();
    replay = std::make_unique<Replay>(algorithm, faces, marginMillimetres / 1000.0, world);
  }
  return *replay;
}

void run(benchmark::State& state, Algorithm algorithm, WorldKind world = WorldKind::SoftRigid) {
  Replay& replay = replayFor(algorithm, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), world);
  thintool::Tool* tool = replay.scene->tool();
  if (replay.scene->ball().m_faces.size() != state.range(0)) {
    state.SkipWithError("the ball does not have the faces asked for");
    return;
  }
  if (replay.pairs.empty()) {
    state.SkipWithError("no pair between the tool and the ball in the captured step");
    return;
  }
  double contacts = 0;
  double facesNear = 0;
  double facesWalked = 0;
  double tests = 0;
  double detect = 0;
  double respond = 0;
  long allocated = 0;
  for (auto _ : state) {
    replay.restore();
    const long before = test::allocationCount();
    state.SetIterationTime(replay.runPairs());
    allocated += test::allocationCount() - before;
    if (tool != nullptr && world != WorldKind::Deformable) {
      const thintool::ToolDiagnostics& d = tool->report().diagnostics;
      contacts += d.detection.colliding;
      facesNear += d.detection.facesGathered;
      facesWalked += d.detection.facesWalked;
      tests += d.detection.triangleTests;
      detect += d.detectionMicroseconds;
      respond += d.responseMicroseconds;
    } else {
      contacts += static_cast<double>(replay.countStockContacts());
    }
  }
  if (replay.movedFarNodes()) {
    state.SkipWithError("the collision stage moved a node the replay does not restore");
    return;
  }
  const double n = static_cast<double>(state.iterations());
  const btSoftBody& ball = replay.scene->ball();
  state.counters["softFaces"] = ball.m_faces.size();
  state.counters["pairs"] = static_cast<double>(replay.pairs.size());
  state.counters["contacts"] = contacts / n;
  state.counters["stepContacts"] = static_cast<double>(replay.stepContacts);
  state.counters["stepUs"] = replay.stepMicroseconds;
  state.counters["allocs"] = static_cast<double>(allocated) / n;
  if (tool != nullptr) {
    state.counters["lastWordUs"] = replay.stepLastWordMicroseconds;
    state.counters["sharedPassUs"] = replay.stepSharedPassMicroseconds;
    state.counters["guardUs"] = replay.stepGuardMicroseconds;
  }
  // In the deformable world the tool's pairs are Bullet's (ToolDiagnostics::stockPairs): only the
  // last word is ThinTool's.
  if (tool != nullptr && world != WorldKind::Deformable) {
    state.counters["toolNodes"] = tool->nodeCount();
    state.counters["facesNear"] = facesNear / n;
    state.counters["facesWalked"] = facesWalked / n;
    state.counters["facesInSweptBox"] = replay.facesInSweptBox;
    state.counters["tests"] = tests / n;
    state.counters["detectUs"] = detect / n;
    state.counters["responseUs"] = respond / n;
    state.counters["stepDetectUs"] = replay.stepDetectMicroseconds;
    state.counters["stepFacesNear"] = replay.stepFacesNear;
  } else {
    state.counters["nodesNear"] = replay.nodesNear;
  }
}

void StockHandler(benchmark::State& state) { run(state, Algorithm::StockE); }
void ThinToolHandler(benchmark::State& state) { run(state, Algorithm::ThinTool); }
void ThinToolPaperHandler(benchmark::State& state) { run(state, Algorithm::ThinToolPaper); }
void StockHandlerSoftMultiBody(benchmark::State& state) { run(state, Algorithm::StockE, WorldKind::SoftMultiBody); }
void ThinToolHandlerSoftMultiBody(benchmark::State& state) {
  run(state, Algorithm::ThinTool, WorldKind::SoftMultiBody);
}
void StockHandlerDeformable(benchmark::State& state) { run(state, Algorithm::StockE, WorldKind::Deformable); }
void ThinToolHandlerDeformable(benchmark::State& state) { run(state, Algorithm::ThinTool, WorldKind::Deformable); }

// Arguments: the ball's faces (128 is the paper's ball) and its margin in mm, ThinTool's skin: stock
// E's 50 mm, and 5 mm (DetectionBench's skin) for both algorithms at two sizes, where the margin's
// share of the cost shows.
#define THINTOOL_HANDLER_SIZES                                                                     \
  ->Args({128, 50})->Args({1024, 50})->Args({4096, 50})->Args({16384, 50})->Args({65536, 50}) \
      ->Args({4096, 5})->Args({65536, 5})
BENCHMARK(StockHandler) THINTOOL_HANDLER_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(ThinToolHandler) THINTOOL_HANDLER_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(ThinToolPaperHandler) THINTOOL_HANDLER_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
// The same scene in the soft multibody world (PyBullet's soft world), at three sizes.
#define THINTOOL_HANDLER_WORLD_SIZES ->Args({128, 50})->Args({4096, 50})->Args({65536, 50})
BENCHMARK(StockHandlerSoftMultiBody) THINTOOL_HANDLER_WORLD_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(ThinToolHandlerSoftMultiBody) THINTOOL_HANDLER_WORLD_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(StockHandlerDeformable) THINTOOL_HANDLER_WORLD_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(ThinToolHandlerDeformable) THINTOOL_HANDLER_WORLD_SIZES->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace thintool::scenes
