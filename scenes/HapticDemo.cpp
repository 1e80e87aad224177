// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "HapticDemo.h"

#include "StillStretches.h"

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace thintool::scenes {

haptics::HapticLoopSettings HapticDemoSettings::defaultLoop() {
  haptics::HapticLoopSettings loop;
  loop.rate = 1000;
  // A Falcon's ±5 cm reach becomes ±0.5 m over the 1 m ball.
  loop.workspaceScale = 10;
  // Against the 50 g the hand feels of the tool, 3 N·s/m would leave the coupling ringing
  // (damping ratio 0.1); 10 gives 0.4, far above the hold's bound of 1.5.
  loop.coupling.damping = 10;
  return loop;
}

ToolOptions HapticDemoSettings::defaultToolOptions() {
  ToolOptions options;
  options.force.enabled = true;
  options.force.measure = DeformationMeasure::Indentation;
  // With the workspace scaled by 10 the hand feels 10 times the tissue's force on the tool.
  options.force.huntCrossley.stiffness = 0.8;
  options.force.huntCrossley.damping = 0.4;
  options.force.huntCrossley.exponent = 1.5;
  // The paper's spatula is frictionless. With the library's default friction the first hold's
  // force at the hand rises slowly as the ball creeps under the nodes stuck to the spatula, and
  // wobbles: 4.2 % peak to peak in lockstep in Bullet's float build, 5.4 % in its float64 build,
  // against 3.2 % without (falcon_demo --fast [--friction]).
  options.response.friction.enabled = false;
  return options;
}

std::vector<HapticHold> findHolds(const std::vector<HapticSample>& trace, double settle, double minimum) {
  std::vector<HapticHold> holds;
  forEachStillStretch(trace, settle, minimum, [&](std::size_t settled, std::size_t last) {
    HapticHold hold;
    hold.from = trace[settled].time;
    hold.to = trace[last].time;
    double low = 1e300, high = 0, sum = 0;
    int touching = 0;
    for (std::size_t i = settled; i <= last; ++i) {
      touching += length(trace[i].contactForce) > 0 ? 1 : 0;
      const double force = length(trace[i].deviceForce);
      low = std::min(low, force);
      high = std::max(high, force);
      sum += force;
    }
    const auto count = static_cast<int>(last - settled + 1);
    if (10 * touching < count) return;
    hold.meanForce = sum / count;
    hold.peakToPeak = high - low;
    holds.push_back(hold);
  });
  return holds;
}

HapticDemoResult runHapticDemo(const HapticDemoSettings& settings, haptics::Device& device) {
  SceneSettings sceneSettings;
  sceneSettings.tool = ToolShape::Plate;
  sceneSettings.timeStep = 1 / settings.physicsRate;
  sceneSettings.toolOptions = settings.toolOptions;
  SoftBallScene scene(sceneSettings);
  scene.settle();

  haptics::HapticLoopSettings loopSettings = settings.loop;
  loopSettings.workspaceOffset = {0, scene.ballTop() + settings.originAboveTop, 0};
  haptics::HapticLoop loop(device, loopSettings);

  // The tool starts where the device's origin maps, held by the coupling: no gravity (the hand
  // carries it), no rotation (a Falcon has three translations).
  const Vec3 start = loopSettings.workspaceOffset;
  scene.makeToolDynamic(settings.toolMass, btTransform(btQuaternion::getIdentity(), toBt(start)));
  btRigidBody& tool = scene.toolBody();
  tool.setLinearFactor(btVector3(1, 1, 1));
  tool.setGravity(btVector3(0, 0, 0));
  tool.setActivationState(DISABLE_DEACTIVATION);
  loop.publishTool(start, {});

  const std::vector<std::array<int, 3>> faces = faceIndices(scene.ball());
  BoxGroundTruth truth;
  truth.start(scene.toolBox(), nodePositions(scene.ball()), faces);

  HapticDemoResult result;
  const double dt = 1 / settings.physicsRate;
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  if (settings.realTime) {
    loop.start();
  }
  auto next = Clock::now();
  double physicsMicroseconds = 0;
  for (int step = 0;; ++step) {
    const double now = step * dt;
    if (settings.realTime) {
      if (!loop.running()) {
        break;
      }
    } else if (!loop.tick(now)) {
      break;
    }
    const Vec3 position = toVec3(tool.getCenterOfMassPosition());
    const Vec3 velocity = toVec3(tool.getLinearVelocity());
    tool.applyCentralForce(toBt(loop.toolForce(position, velocity)));
    physicsMicroseconds += scene.step();
    loop.publishTool(toVec3(tool.getCenterOfMassPosition()), toVec3(tool.getLinearVelocity()));
    truth.update(scene.toolBox(), nodePositions(scene.ball()), faces);

    const ToolStepReport& report = scene.tool()->report();
    HapticSample sample;
    sample.time = now;
    sample.device = loop.device().worldPosition;
    sample.tool = toVec3(tool.getCenterOfMassPosition());
    sample.deviceForce = loop.deviceForce();
    sample.contactForce = report.contactForce.force;
    sample.contacts = static_cast<int>(report.contacts.size());
    for (const ToolFaceForce& face : report.contactForce.faces) {
      sample.largestDeformation = std::max(sample.largestDeformation, face.face.deformation);
    }
    result.trace.push_back(sample);
    if (settings.realTime) {
      next += period;
      std::this_thread::sleep_until(next);
    }
  }
  loop.stop();
  result.steps = static_cast<int>(result.trace.size());
  result.physicsMicrosecondsPerStep = result.steps > 0 ? physicsMicroseconds / result.steps : 0;
  result.loop = loop.statistics();
  result.metrics = truth.metrics();
  return result;
}

}  // namespace thintool::scenes
