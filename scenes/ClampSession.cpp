// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ClampSession.h"

#include "ClampStage.h"
#include "StillStretches.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

namespace thintool::scenes {

haptics::HapticLoopSettings ClampSessionSettings::defaultLoop() {
  haptics::HapticLoopSettings loop;
  loop.rate = 1000;
  loop.workspaceScale = 20;
  return loop;
}

haptics::ClampMapping ClampSessionSettings::defaultMapping() {
  haptics::ClampMapping mapping;
  mapping.workspaceScale = 20;
  mapping.openingAtCentre = ClampSettings{}.maxOpening;
  mapping.radiansPerMetre = 30;
  return mapping;
}

ClampSessionResult runClampSession(const ClampSessionSettings& settings, haptics::Device& device) {
  constexpr double kSqueeze = 0.2;  // as runClamp's: the trajectories close the clamp that far
  ClampStage stage(settings.body, settings.friction, settings.timeStep, kSqueeze);
  haptics::HapticLoop loop(device, settings.loop);
  ClampSessionResult result;
  result.restCentreHeight = stage.restCentreHeight();
  result.bodyWeight = stage.bodyMass() * double(-stage.world().getGravity().y());

  const double dt = settings.timeStep;
  const double tickPeriod = 1 / settings.loop.rate;
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  if (settings.realTime) {
    loop.start();
  }
  auto next = Clock::now();
  long tick = 0;
  for (int step = 0;; ++step) {
    const double end = (step + 1) * dt;
    if (settings.realTime) {
      if (!loop.running()) break;
    } else {
      bool alive = true;
      for (; alive && double(tick) * tickPeriod <= end; ++tick) alive = loop.tick(double(tick) * tickPeriod);
      if (!alive) break;
    }
    const haptics::DeviceSnapshot snapshot = loop.device();
    if (!snapshot.valid) {  // the loop's thread has not read the device yet
      next += period;
      std::this_thread::sleep_until(next);
      continue;
    }
    haptics::DeviceState state;
    state.time = snapshot.time;
    state.position = snapshot.position;
    state.buttons = snapshot.buttons;
    const haptics::ClampCommand command = haptics::mapDeviceToClamp(state, settings.mapping);
    btTransform pose = stage.handle();
    double opening = stage.clamp().opening();
    if (std::isfinite(command.planeX) && std::isfinite(command.planeY) && std::isfinite(command.opening)) {
      pose.setOrigin(stage.handle().getOrigin() + btVector3(btScalar(command.planeX), btScalar(command.planeY), 0));
      opening = command.opening;
    }
    ClampForces forces;
    const ClampSample sample = stage.step(pose, opening, "", forces);
    const Vec3 onClamp = forces.onJaw[0] + forces.onJaw[1];
    loop.publishToolForce(onClamp);

    ClampSessionSample out;
    out.time = sample.time;
    out.device = snapshot.position;
    out.opening = sample.opening;
    out.bodyCentreHeight = sample.bodyCentreHeight;
    out.onClamp = onClamp;
    out.deviceForce = loop.deviceForce();
    out.bodyNetForce = sample.bodyNetForce;
    out.bodyPressure = sample.bodyPressure;
    result.trace.push_back(out);
    result.crossed = sample.crossed;
    result.jawEverInside = result.jawEverInside || sample.jawInside;
    if (settings.observer && !settings.observer(stage.world(), stage.clamp(), out, loop)) break;
    if (settings.realTime) {
      next += period;
      std::this_thread::sleep_until(next);
    }
  }
  loop.stop();
  result.steps = static_cast<int>(result.trace.size());
  result.physicsMicrosecondsPerStep = result.steps > 0 ? stage.wallMicroseconds() / result.steps : 0;
  result.loop = loop.statistics();
  return result;
}

std::vector<ClampSessionHold> findHolds(const std::vector<ClampSessionSample>& trace, double settle, double minimum) {
  std::vector<ClampSessionHold> holds;
  forEachStillStretch(trace, settle, minimum, [&](std::size_t settled, std::size_t last) {
    ClampSessionHold hold;
    hold.from = trace[settled].time;
    hold.to = trace[last].time;
    double low = 1e300, high = 0;
    for (std::size_t i = settled; i <= last; ++i) {
      const ClampSessionSample& s = trace[i];
      hold.bodyCentreHeight += s.bodyCentreHeight;
      hold.onClamp += s.onClamp;
      hold.deviceForce += s.deviceForce;
      hold.bodyNetForce += s.bodyNetForce;
      hold.bodyPressure += s.bodyPressure;
      low = std::min(low, length(s.deviceForce));
      high = std::max(high, length(s.deviceForce));
    }
    const double count = double(last - settled + 1);
    hold.bodyCentreHeight /= count;
    hold.onClamp = hold.onClamp / count;
    hold.deviceForce = hold.deviceForce / count;
    hold.bodyNetForce = hold.bodyNetForce / count;
    hold.bodyPressure = hold.bodyPressure / count;
    hold.deviceForcePeakToPeak = high - low;
    holds.push_back(hold);
  });
  return holds;
}

}  // namespace thintool::scenes
