// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "force/ContactForce.h"

#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thintool {
namespace {

HuntCrossley model(Real k, Real lambda, Real n) {
  HuntCrossley hc;
  hc.stiffness = k;
  hc.damping = lambda;
  hc.exponent = n;
  return hc;
}

TEST(HuntCrossley, ZeroWithoutDeformationAndContinuousAtFirstTouch) {
  const HuntCrossley hc = model(500, 80, 1.5);
  EXPECT_EQ(huntCrossleyForce(hc, 0, 3.0), 0);
  EXPECT_EQ(huntCrossleyForce(hc, -0.01, 3.0), 0);
  // Arriving fast, the force still starts from 0: the damping term carries xⁿ too.
  Real previous = 0;
  for (Real x = 1e-9; x < 1e-3; x *= 10) {
    const Real force = huntCrossleyForce(hc, x, 3.0);
    EXPECT_GE(force, previous);
    EXPECT_LT(force, (500 + 80 * 3.0) * std::pow(x, 1.5) * (1 + 1e-12));
    previous = force;
  }
  EXPECT_LT(huntCrossleyForce(hc, 1e-9, 3.0), 1e-9);
}

TEST(HuntCrossley, NeverPullsOnFastWithdrawal) {
  const HuntCrossley hc = model(500, 80, 1.5);
  // ẋ < −k/λ makes k + λ·ẋ negative: the unclamped law would pull the tool back in.
  const Real withdrawal = -2 * 500.0 / 80;
  EXPECT_EQ(huntCrossleyForce(hc, 0.01, withdrawal), 0);
  EXPECT_GT(huntCrossleyForce(hc, 0.01, -0.5 * 500.0 / 80), 0);
}

TEST(HuntCrossley, LinearSpringWhenExponentOneAndNoDamping) {
  const HuntCrossley hc = model(300, 0, 1);
  for (Real x : {0.001, 0.01, 0.1, 0.5}) {
    EXPECT_NEAR(huntCrossleyForce(hc, x, 7.0), 300 * x, 1e-12);
  }
}

TEST(HuntCrossley, ScalesWithTheExponent) {
  const HuntCrossley hc = model(300, 20, 1.7);
  const Real x = 0.02;
  EXPECT_NEAR(huntCrossleyForce(hc, 2 * x, 0.1) / huntCrossleyForce(hc, x, 0.1), std::pow(2.0, 1.7), 1e-9);
}

TEST(HuntCrossley, NonFiniteInputGivesZero) {
  const HuntCrossley hc = model(300, 20, 1.5);
  EXPECT_EQ(huntCrossleyForce(hc, std::nan(""), 1), 0);
  EXPECT_EQ(huntCrossleyForce(hc, 0.01, std::nan("")), 0);
  EXPECT_EQ(huntCrossleyForce(hc, INFINITY, 1), 0);
}

// A closed sphere as the soft body; the scripted press pushes the nodes near its top down.
struct Press {
  ConvexMesh sphere = test::icosphere(1, {0, 0, 0}, 2);
  SoftPatch patch = test::patchOf(sphere);
  RestShape rest;
  ForceResult result;
  std::vector<FaceForce>& forces = result.faces;
  std::vector<PatchContact> contacts;
  std::vector<Vec3> anchors;
  RigidFit fit;
  ForceSettings settings;
  // A 4 × 0.02 × 4 plate, parked far above unless a test lowers it: the contacts alone count.
  ToolModel plate = buildToolModel(makeBoxMesh({2, 0.01, 2}), ToolModelSettings{});
  Pose platePose{Mat3{}, {0, 100, 0}};
  Real skin = 0.01;
  static constexpr Real kDt = 0.001;

  Press() {
    rest.capture(patch.positions, patch.inverseMasses, 64);
    result.history.resize(patch.faceCount());
    settings.enabled = true;
    settings.huntCrossley = model(200, 0, 1);
    // Every node above y = 0.9 is held by a contact of the tool's underside, pushing down.
    for (Index v = 0; v < patch.vertexCount(); ++v) {
      if (patch.positions[v].y > 0.9) {
        PatchContact contact;
        contact.kind = ContactKind::SoftNode;
        contact.softNodeCount = 1;
        contact.softNodes[0] = patch.nodeIds[v];
        contact.patchVertices[0] = v;
        contact.normal = {0, -1, 0};
        contacts.push_back(contact);
      }
    }
  }
  // Moves the body rigidly by (rotation, shift) from rest, then pushes the top down by depth
  // along the rotated vertical.
  void pose(const Mat3& rotation, const Vec3& shift, Real depth) {
    patch.previousPositions = patch.positions;
    for (Index v = 0; v < patch.vertexCount(); ++v) {
      const Vec3 at = rest.position(patch.nodeIds[v]);
      const Vec3 pressed = at.y > 0.9 ? at - Vec3{0, depth, 0} : at;
      patch.positions[v] = rotation * pressed + shift;
    }
    for (auto& contact : contacts) {
      contact.normal = rotation * Vec3{0, -1, 0};
    }
    anchors.clear();
    for (Index node : rest.anchors()) {
      anchors.push_back(patch.positions[node]);
    }
    fit = fitRigidMotion(rest, anchors, fit);
  }
  Vec3 net() const {
    Vec3 sum;
    for (const FaceForce& f : forces) {
      sum += f.force;
    }
    return sum;
  }
  void step() {
    computeContactForces({plate, platePose, platePose, kDt, skin}, patch, contacts, {settings, rest, fit}, result);
  }
};

TEST(ContactForce, OffComputesNothing) {
  Press press;
  press.settings.enabled = false;
  press.pose(Mat3{}, {}, 0.05);
  press.step();
  EXPECT_TRUE(press.forces.empty());
}

TEST(ContactForce, IndentationPushesTheToolBackAlongTheContactNormal) {
  Press press;
  press.pose(Mat3{}, {}, 0.05);
  press.step();
  ASSERT_FALSE(press.forces.empty());
  const Vec3 net = press.net();
  EXPECT_GT(net.y, 0);
  EXPECT_NEAR(net.x, 0, 1e-9 * net.y);
  for (const FaceForce& f : press.forces) {
    EXPECT_GE(f.force.y, 0);
    EXPECT_LE(f.deformation, 0.05 + 1e-9);  // a face's centroid moves at most as far as its nodes
  }
  // Deeper press, larger force; linear law: proportional for faces wholly under the tool.
  press.pose(Mat3{}, {}, 0.10);
  press.step();
  EXPECT_GT(press.net().y, 1.9 * net.y);
}

TEST(ContactForce, IndentationIgnoresTheBodysRigidMotionAndTheCentroidMeasureDoesNot) {
  const Mat3 tilt = rotationAboutAxis({0, 0, 1}, 0.6);
  const Vec3 shift{0.3, -0.2, 0.5};
  Press still;
  still.pose(Mat3{}, {}, 0.04);
  still.step();
  Press moved;
  moved.pose(tilt, shift, 0.04);
  moved.step();
  ASSERT_EQ(still.forces.size(), moved.forces.size());
  // The shape matching sees the dent too (its anchors include pressed nodes), hence the tolerance.
  EXPECT_NEAR(length(moved.net()), length(still.net()), 0.05 * length(still.net()));
  EXPECT_NEAR(dot(normalizedOrZero(moved.net()), tilt * Vec3{0, 1, 0}), 1, 1e-3);

  Press paper;
  paper.settings.measure = DeformationMeasure::CentroidDisplacement;
  paper.pose(tilt, shift, 0.04);
  paper.step();
  Press paperStill;
  paperStill.settings.measure = DeformationMeasure::CentroidDisplacement;
  paperStill.pose(Mat3{}, {}, 0.04);
  paperStill.step();
  EXPECT_GT(length(paper.net()), 5 * length(paperStill.net()));
}

TEST(ContactForce, CentroidMeasureIsThePapersDistanceFromRest) {
  Press press;
  press.settings.measure = DeformationMeasure::CentroidDisplacement;
  press.pose(Mat3{}, {0, -0.02, 0}, 0);  // the body sinks 2 cm, the tool only follows
  press.step();
  ASSERT_FALSE(press.forces.empty());
  for (const FaceForce& f : press.forces) {
    EXPECT_NEAR(f.deformation, 0.02, 1e-12);
    EXPECT_NEAR(f.force.y, 200 * 0.02, 1e-9);
  }
}

TEST(ContactForce, RateFollowsAConstantPressAndDampingAddsForce) {
  Press press;
  press.settings.huntCrossley = model(200, 40, 1);
  const Real speed = 0.05;  // m/s
  Real depth = 0;
  for (int i = 0; i < 200; ++i) {
    depth += speed * Press::kDt;
    press.pose(Mat3{}, {}, depth);
    press.step();
  }
  ASSERT_FALSE(press.forces.empty());
  Real springOnly = 0;
  for (const FaceForce& f : press.forces) {
    // Faces wholly under the tool move with it; rim faces move a third or two thirds as fast.
    EXPECT_GT(f.rate, 0);
    EXPECT_LE(f.rate, speed * (1 + 1e-6));
    springOnly += 200 * f.deformation;
  }
  EXPECT_GT(press.net().y, springOnly);
}

TEST(ContactForce, RateFilterSmoothsAJump) {
  Press filtered;
  filtered.settings.rateCutoff = 10;
  Press raw;
  raw.settings.rateCutoff = 0;
  for (Press* press : {&filtered, &raw}) {
    for (int i = 0; i < 5; ++i) {  // touching, still
      press->pose(Mat3{}, {}, 0);
      press->step();
    }
    press->pose(Mat3{}, {}, 0.01);  // a 1 cm jump in one 1 ms step
    press->step();
  }
  ASSERT_FALSE(raw.forces.empty());
  ASSERT_EQ(raw.forces.size(), filtered.forces.size());
  const Real alpha = 1 - std::exp(-2 * kPi * 10 * Press::kDt);
  for (std::size_t i = 0; i < raw.forces.size(); ++i) {
    EXPECT_GT(raw.forces[i].rate, 0);
    EXPECT_NEAR(filtered.forces[i].rate, alpha * raw.forces[i].rate, 1e-9 * raw.forces[i].rate);
  }
}

TEST(ContactForce, NodesTouchingTheToolCollideWithoutAContact) {
  // The projection left the pressed cap on the plate's underside: no contact this step, yet the
  // faces touching the plate deform and push back.
  Press press;
  press.contacts.clear();
  press.pose(Mat3{}, {}, 0.05);
  press.step();
  EXPECT_TRUE(press.forces.empty()) << "the parked plate touches nothing";
  press.platePose.translation = {0, 1 - 0.05 + 0.01 + press.skin, 0};  // underside a skin above the top
  press.skin = 0.1;  // reaches the pressed cap's rim too
  press.step();
  ASSERT_FALSE(press.forces.empty());
  EXPECT_GT(press.net().y, 0);
}

TEST(ContactForce, CustomLawReplacesHuntCrossley) {
  Press press;
  press.settings.law = [](Real x, Real) { return 1000 * x * x; };
  press.pose(Mat3{}, {}, 0.05);
  press.step();
  ASSERT_FALSE(press.forces.empty());
  for (const FaceForce& f : press.forces) {
    EXPECT_NEAR(length(f.force), 1000 * f.deformation * f.deformation, 1e-9);
  }
  press.settings.law = [](Real, Real) { return -5.0; };  // a law that pulls is clamped
  press.step();
  EXPECT_EQ(length(press.net()), 0);
}

TEST(RigidFit, RecoversRotationAndTranslation) {
  const ConvexMesh sphere = test::icosphere(0.5, {1, 2, 3}, 2);
  RestShape rest;
  rest.capture(sphere.vertices, std::vector<Real>(sphere.vertices.size(), 1.0), 32);
  const Mat3 rotation = rotationAboutAxis(normalizedOrZero(Vec3{1, 2, -1}), 2.5);
  const Vec3 shift{-4, 0.5, 2};
  std::vector<Vec3> anchors;
  for (Index node : rest.anchors()) {
    anchors.push_back(rotation * sphere.vertices[node] + shift);
  }
  const RigidFit fit = fitRigidMotion(rest, anchors, RigidFit{});
  for (const Vec3& p : sphere.vertices) {
    EXPECT_NEAR(length(fit.apply(p) - (rotation * p + shift)), 0, 1e-9);
  }
}

}  // namespace
}  // namespace thintool
