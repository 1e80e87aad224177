// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// "Nothing is allocated once the buffers have grown" (docs/design.md), checked: every
// operator new of the program and every allocation through Bullet's btAlignedAlloc is counted, and
// the counts are taken around what Bullet's dispatcher runs for the tool's pairs with the ball (its
// near callback), which for ThinTool is the whole per-step path (gather, detection, response,
// holds). The scene is the paper's with ThinTool's defaults, pressed a quarter of the ball's height
// deep, held, lifted and pressed again: only the first press may grow the buffers (to the most
// contacts, nodes and holds the scene ever has, or, growing by doubling, past it), and the hold, the
// lift and the repeated press and hold must allocate nothing. Its own executable, because
// replacing operator new replaces it for the whole program.

#include <CountingAllocator.h>
#include <SoftBallScene.h>

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <LinearMath/btAlignedAllocator.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

namespace thintool::scenes {
namespace {

// Bullet's near callback is a plain function: the scene being counted is reached through this.
SoftBallScene* counted = nullptr;
long inToolPairs = 0;

void countingNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
  const void* a = pair.m_pProxy0->m_clientObject;
  const void* b = pair.m_pProxy1->m_clientObject;
  const void* ball = &counted->ball();
  const void* ground = &counted->ground();
  const bool toolPair = (a == ball || b == ball) && a != ground && b != ground;
  const long before = test::allocationCount();
  btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
  if (toolPair) {
    inToolPairs += test::allocationCount() - before;
  }
}

enum class Motion { Press, Hold, Lift };

struct Phase {
  const char* name;
  Motion motion;
  long allocations = 0;
  int steps = 0;
  int contactSteps = 0;
};

std::vector<Phase> pressHoldLiftPress(const SceneSettings& settings) {
  test::installCountingBulletAllocator();
  SoftBallScene scene(settings);
  scene.settle();
  counted = &scene;
  auto& dispatcher = *static_cast<btCollisionDispatcher*>(scene.world().getDispatcher());
  dispatcher.setNearCallback(&countingNearCallback);

  const double dt = settings.timeStep;
  const double start = scene.pressStartHeight();
  // Three tenths of the way to the ball's mean height: pressed deeper, the ball squirts out from
  // under the frictionless plate (halfway, it did so in the sanitizer build and not in the others).
  const double bottom = scene.ballTop() - 0.3 * (scene.ballTop() - scene.ballMeanHeight());
  const int moveSteps = static_cast<int>((start - bottom) / (0.5 * dt));  // 0.5 m/s
  std::vector<Phase> phases{{"first press", Motion::Press},
                            {"hold", Motion::Hold},
                            {"lift", Motion::Lift},
                            {"second press", Motion::Press},
                            {"second hold", Motion::Hold}};
  btTransform pose(btQuaternion::getIdentity(), scene.aboveBall(start));
  scene.step(pose);
  // Where the ball's centre has drifted to, across: pressed by a frictionless plate the ball may
  // slide out from under it (which way depends on rounding), so each press starts over the ball.
  btVector3 across(0, 0, 0);
  for (Phase& phase : phases) {
    if (phase.motion == Motion::Press) {
      btVector3 centre(0, 0, 0);
      for (int n = 0; n < scene.ball().m_nodes.size(); ++n) {
        centre += scene.ball().m_nodes[n].m_x;
      }
      centre /= btScalar(scene.ball().m_nodes.size());
      across = centre - scene.aboveBall(centre.y());
    }
    const int steps = phase.motion == Motion::Hold ? 30 : moveSteps;
    for (int i = 1; i <= steps; ++i) {
      const double f = double(i) / steps;
      if (phase.motion == Motion::Press) {
        pose.setOrigin(scene.aboveBall(start + (bottom - start) * f) + across);
      } else if (phase.motion == Motion::Lift) {
        pose.setOrigin(scene.aboveBall(bottom + (start - bottom) * f) + across);
      }
      inToolPairs = 0;
      scene.step(pose);
      phase.allocations += inToolPairs;
      ++phase.steps;
      phase.contactSteps += scene.tool()->report().diagnostics.detection.colliding > 0 ? 1 : 0;
    }
  }
  dispatcher.setNearCallback(&btCollisionDispatcher::defaultNearCallback);
  counted = nullptr;
  for (const Phase& phase : phases) {
    std::printf("%-13s %3d steps, %3d with contacts: %ld allocations in the tool's pairs\n", phase.name, phase.steps,
                phase.contactSteps, phase.allocations);
  }
  return phases;
}

TEST(Allocation, ThinToolStepsAllocateNothingOnceTheBuffersHaveGrown) {
  // ThinTool's default, swept detection; the first press grows the buffers, everything after it
  // must find them grown.
  const std::vector<Phase> phases = pressHoldLiftPress(SceneSettings{});
  EXPECT_GT(phases[0].allocations, 0);  // the count sees the growth
  for (std::size_t k = 1; k < phases.size(); ++k) {
    EXPECT_GT(phases[k].contactSteps, 0) << phases[k].name;
    EXPECT_EQ(phases[k].allocations, 0) << phases[k].name;
  }
}

}  // namespace
}  // namespace thintool::scenes
