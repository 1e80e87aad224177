// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The Falcon demo's scene on its shipped trajectory, replayed in lockstep: the input the demo
// plays headless is the input of this test.

#include "HapticDemo.h"

#include <thintool/haptics/ReplayDevice.h>

#include <gtest/gtest.h>

namespace thintool::scenes {
namespace {

struct Window {
  double from;
  double to;
};

TEST(FalconDemo, ShippedTrajectoryFeelsTheTissueAndNeverPassesThrough) {
  haptics::ReplayDevice device = haptics::ReplayDevice::fromFile(THINTOOL_FALCON_TRAJECTORY);
  const HapticDemoSettings settings;
  const HapticDemoResult result = runHapticDemo(settings, device);
  ASSERT_GT(result.steps, 6000);
  EXPECT_EQ(result.metrics.crossed, 0);
  EXPECT_FALSE(result.metrics.everInside);

  const double scale = settings.loop.workspaceScale;
  const Window approach{0.0, 1.0};  // the spatula is still above the ball
  // Pressing, 5 to 10 cm into the ball. (Held still deeper in, the squashed ball can sag away from
  // the plate for a while; how long differs between Bullet's float and float64 builds.)
  const Window press{1.8, 2.1};
  const Window withdrawal{4.0, 4.1};
  double holdDevice = 0;
  double holdTissue = 0;
  int holdSamples = 0;
  for (const HapticSample& s : result.trace) {
    EXPECT_LE(length(s.deviceForce), 8 + 1e-9) << "at " << s.time;
    EXPECT_TRUE(isFinite(s.contactForce) && isFinite(s.deviceForce)) << "at " << s.time;
    if (s.time >= approach.from && s.time < approach.to) {
      EXPECT_EQ(length(s.contactForce), 0) << "at " << s.time;
      EXPECT_LT(length(s.deviceForce), 0.05) << "at " << s.time;
    }
    if (s.time >= withdrawal.from && s.time < withdrawal.to) {
      EXPECT_GE(s.contactForce.y, 0) << "the tissue never pulls the spatula back, at " << s.time;
    }
    if (s.time >= press.from && s.time < press.to) {
      EXPECT_GE(s.contactForce.y, 0) << "at " << s.time;
      holdDevice += s.deviceForce.y;
      holdTissue += s.contactForce.y;
      ++holdSamples;
    }
  }
  ASSERT_GT(holdSamples, 0);
  holdDevice /= holdSamples;
  holdTissue /= holdSamples;
  // The coupling carries the tissue's push to the hand, scaled up by the workspace (the tool's
  // lag behind the device adds the coupling's damping).
  EXPECT_GT(holdDevice, 0.3);
  EXPECT_GT(holdTissue, 0);
  EXPECT_NEAR(holdDevice, scale * holdTissue, 0.4 * holdDevice);
}

}  // namespace
}  // namespace thintool::scenes
