// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The clamp under the hand, on the shipped grasp trajectories replayed in lockstep: the input
// clamp_demo --session plays is the input of these tests.

#include "ClampSession.h"

#include <thintool/haptics/ReplayDevice.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace thintool::scenes {
namespace {

class ClampSession : public ::testing::TestWithParam<ClampBody> {};

TEST_P(ClampSession, TheReplayedGraspLiftsTheBodyAndTheHandFeelsWhatTheJawsCarry) {
  const ClampBody body = GetParam();
  haptics::ReplayDevice device = haptics::ReplayDevice::fromFile(std::string(THINTOOL_CLAMP_TRAJECTORIES) +
                                                                 "/grasp-" + clampBodyName(body) + ".csv");
  ClampSessionSettings settings;
  settings.body = body;
  const ClampSessionResult result = runClampSession(settings, device);
  ASSERT_GT(result.steps, 400);
  EXPECT_EQ(result.crossed, 0);
  EXPECT_FALSE(result.jawEverInside);
  for (const ClampSessionSample& s : result.trace) {
    ASSERT_TRUE(isFinite(s.deviceForce) && isFinite(s.onClamp)) << "at " << s.time;
    EXPECT_LE(length(s.deviceForce), 8 + 1e-9) << "at " << s.time;
  }

  // The trajectory holds the device still, the body lifted, from 3 s to 5 s.
  const ClampSessionHold* held = nullptr;
  const std::vector<ClampSessionHold> holds = findHolds(result.trace);
  for (const ClampSessionHold& hold : holds) {
    if (hold.from < 4 && hold.to > 4) held = &hold;
  }
  ASSERT_NE(held, nullptr);
  EXPECT_GT(held->bodyCentreHeight, result.restCentreHeight + 0.9) << "lifted with the clamp's metre";
  const double scale = settings.loop.workspaceScale;
  // The hand feels the jaws' load, scaled down by the workspace.
  EXPECT_NEAR(held->deviceForce.y * scale, held->onClamp.y, 0.01 * std::abs(held->onClamp.y));
  // The jaws carry the weight, less what the body's own pressure carries (a squeezed mesh's
  // pressure forces do not cancel), as the body's momentum balance measures it.
  EXPECT_NEAR(held->bodyNetForce.y, result.bodyWeight, 0.02 * result.bodyWeight);
  EXPECT_NEAR(-held->onClamp.y + held->bodyPressure.y, held->bodyNetForce.y, 0.02 * result.bodyWeight);
  // What the pressure carries depends on how the jaws squeezed the mesh: the vessel's 1.1 N of
  // 10 N (docs/guide/clamp.md).
  EXPECT_NEAR(-held->onClamp.y, result.bodyWeight, 0.15 * result.bodyWeight);
  if (body == ClampBody::Sphere) {
    EXPECT_NEAR(-held->onClamp.y, result.bodyWeight, 0.1 * result.bodyWeight);
  }
}

INSTANTIATE_TEST_SUITE_P(SphereAndVessel, ClampSession, ::testing::Values(ClampBody::Sphere, ClampBody::Vessel),
                         [](const ::testing::TestParamInfo<ClampBody>& body) {
                           return std::string(clampBodyName(body.param));
                         });

}  // namespace
}  // namespace thintool::scenes
