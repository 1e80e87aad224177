// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The clamp (paper §IV.A): its hinge and its errors, and the grasp: closing on the sphere and on
// the vessel no node crosses a jaw and no jaw ends inside; with friction the body is lifted, stays
// in the jaws while held and drops when released; without friction it slips out; at rest the two
// jaws' squeezes are equal and opposite.

#include "ClampScene.h"
#include "SoftWorld.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <cmath>

namespace thintool::scenes {
namespace {

using World = SoftWorld;

TEST(Clamp, JawsHingeAboutTheHandleAndTheOpeningStaysInRange) {
  World w;
  ClampSettings settings;
  settings.maxOpening = 1;
  Clamp clamp(w.world, settings, btTransform::getIdentity(), 2);
  EXPECT_EQ(clamp.opening(), 1) << "clamped to maxOpening";
  clamp.setPose(btTransform::getIdentity(), -1);
  EXPECT_EQ(clamp.opening(), 0);
  // Closed, the inner faces meet on the handle's x axis: the upper jaw's underside at y = 0.
  const btTransform upper = clamp.jawPose(0, btTransform::getIdentity(), 0);
  EXPECT_NEAR(upper.getOrigin().y(), settings.jawHalfExtents.y, 1e-6);
  EXPECT_NEAR(upper.getOrigin().x(), settings.jawHalfExtents.x, 1e-6);
  // Open by a, the jaws' axes leave the hinge at ±a/2.
  const btTransform lower = clamp.jawPose(1, btTransform::getIdentity(), 0.5);
  const btVector3 axis = lower.getBasis().getColumn(0);
  EXPECT_NEAR(std::atan2(axis.y(), axis.x()), -0.25, 1e-6);
  EXPECT_NE(clamp.jaw(0).name().find("upper jaw"), std::string::npos);
  clamp.setPose(btTransform::getIdentity(), std::nan(""));
  EXPECT_EQ(clamp.opening(), 0) << "a NaN opening is ignored";
}

TEST(Clamp, InvalidSettingsNameTheClampAndTheField) {
  World w;
  ClampSettings settings;
  settings.name = "forceps";
  settings.maxOpening = 4;
  try {
    Clamp clamp(w.world, settings, btTransform::getIdentity(), 0.5);
    FAIL() << "accepted maxOpening 4 rad";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("forceps"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("maxOpening"), std::string::npos) << error.what();
  }
  settings.maxOpening = 1;
  settings.jawOptions.response.friction.kineticCoefficient = 2;  // above the static one
  EXPECT_THROW(Clamp(w.world, settings, btTransform::getIdentity(), 0.5), Error);
  EXPECT_EQ(w.world.getNumCollisionObjects(), 0) << "a refused clamp leaves nothing behind";
}

class Grasp : public ::testing::TestWithParam<ClampBody> {};

TEST_P(Grasp, WithFrictionTheBodyIsLiftedHeldAndDropped) {
  ClampRunSettings settings;
  settings.body = GetParam();
  const ClampRun run = runClamp(settings);
  EXPECT_EQ(run.crossed, 0);
  EXPECT_FALSE(run.jawEverInside);
  const double lifted = run.restCentreHeight + 0.9 * settings.liftHeight;
  for (const ClampSample& s : run.samples) {
    if (s.phase == "hold") {
      ASSERT_GT(s.bodyCentreHeight, lifted) << "at " << s.time << " s the body slipped";
    }
  }
  EXPECT_LT(run.droppedCentreHeight, run.restCentreHeight + 0.2) << "released, it falls back";
  // Held up, the jaws carry its weight: the body's net force but gravity is m·g upwards.
  double support = 0;
  int samples = 0;
  for (const ClampSample& s : run.samples) {
    if (s.phase == "hold" && s.time > run.samples.back().time - 3.5) {
      support += s.bodyNetForce.y;
      ++samples;
    }
  }
  EXPECT_NEAR(support / samples, 10, 1) << "1 kg at g = 10 m/s²";
  // The jaws' reports say what carries it: the response's moves and the soft solver's holds, with
  // the body's own pressure (which does not cancel on a squeezed mesh) making up the balance.
  double reported = 0;
  double pressure = 0;
  for (const ClampSample& s : run.samples) {
    if (s.phase == "hold" && s.time > run.samples.back().time - 3.5) {
      reported += s.onBody.y;
      pressure += s.bodyPressure.y;
    }
  }
  EXPECT_NEAR((reported + pressure) / samples, support / samples, 0.02 * std::abs(support / samples));
  EXPECT_GT(reported / samples, 0.7 * 10) << "the jaws carry most of the weight";
  // At rest the squeezes on the two jaws are equal and opposite, within 15 % (the clamp's V pushes
  // the body out of the jaws, and each jaw's share of the friction that holds it differs).
  EXPECT_GT(run.upperSqueeze * -run.lowerSqueeze, 0) << "opposite signs";
  EXPECT_LT(std::abs(run.upperSqueeze + run.lowerSqueeze),
            0.15 * std::max(std::abs(run.upperSqueeze), std::abs(run.lowerSqueeze)));
}

TEST_P(Grasp, WithoutFrictionTheBodySlipsOut) {
  ClampRunSettings settings;
  settings.body = GetParam();
  settings.friction = false;
  const ClampRun run = runClamp(settings);
  EXPECT_EQ(run.crossed, 0);
  EXPECT_FALSE(run.jawEverInside);
  EXPECT_LT(run.liftedCentreHeight, run.restCentreHeight + 0.5 * settings.liftHeight);
}

INSTANTIATE_TEST_SUITE_P(SphereAndVessel, Grasp, ::testing::Values(ClampBody::Sphere, ClampBody::Vessel),
                         [](const ::testing::TestParamInfo<ClampBody>& body) {
                           return std::string(clampBodyName(body.param));
                         });

}  // namespace
}  // namespace thintool::scenes
