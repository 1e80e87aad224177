// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "../../src/bullet/ToolReaction.h"
#include "geometry/ConvexMesh.h"
#include "tool/ToolModel.h"

#include <thintool/bullet/Convert.h>

#include <LinearMath/btTransformUtil.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace thintool::detail {
namespace {

constexpr btScalar kStep = btScalar(1.0 / 60);
constexpr double kTolerance = 1e-4;  // m, the ground truth's (eval/GroundTruth.h)

// A dynamic box at the origin moving at velocity, not turning.
std::unique_ptr<btRigidBody> movingBox(btBoxShape& shape, btScalar mass, const btVector3& velocity) {
  btVector3 inertia(0, 0, 0);
  shape.calculateLocalInertia(mass, inertia);
  auto body = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(mass, nullptr, &shape, inertia));
  body->setLinearVelocity(velocity);
  return body;
}

TEST(ToolReaction, AHeavyToolGivesUpTheNodesMomentum) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, 10, btVector3(0, -1, 0));
  // A 10 g node at rest under the plate, pushed 1 cm down by it.
  const btVector3 displacement(0, btScalar(-0.01), 0);
  const btScalar impulse = applyNodeReaction(*tool, btVector3(0, btScalar(-0.02), 0), displacement,
                                             100, 1 / kStep, btVector3(0, 0, 0));
  EXPECT_NEAR(impulse, 0.01 * 0.01 / kStep, 1e-6);
  EXPECT_NEAR(tool->getLinearVelocity().y(), -1 + impulse / 10, 1e-6);
}

TEST(ToolReaction, ALightToolIsNeverSentBack) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, btScalar(0.001), btVector3(0, -1, 0));
  // A 1 kg node at rest, a thousand times the plate, moved along with it: the node's momentum
  // would send the plate up at 999 m/s; an inelastic collision all but stops it.
  const btVector3 displacement(0, -kStep, 0);
  applyNodeReaction(*tool, btVector3(0, btScalar(-0.02), 0), displacement, 1, 1 / kStep, btVector3(0, 0, 0));
  EXPECT_LE(tool->getLinearVelocity().y(), 0);
  EXPECT_GE(tool->getLinearVelocity().y(), btScalar(-0.01));
  EXPECT_NEAR(tool->getAngularVelocity().length(), 0, 1e-6);
}

TEST(ToolReaction, AThinNeedleIsNotSpunAboutItsAxis) {
  // A 1 kg needle 2 mm thick along x, moving at 1 m/s along z: almost no inertia about its axis.
  // It pushes a 1 kg node at rest at its surface, off its centre line.
  btBoxShape shape(btVector3(0.25f, 0.001f, 0.001f));
  auto tool = movingBox(shape, 1, btVector3(0, 0, 1));
  const btVector3 nodePosition(0, btScalar(0.001), btScalar(0.001));
  const btVector3 arm = nodePosition - tool->getCenterOfMassPosition();
  const btVector3 displacement(0, 0, btScalar(0.01));
  applyNodeReaction(*tool, nodePosition, displacement, 1, 1 / kStep, btVector3(0, 0, 0));
  const btScalar along = tool->getVelocityInLocalPoint(arm).z();
  EXPECT_GE(along, btScalar(-1e-4)) << "sent back";
  EXPECT_LE(along, btScalar(1 + 1e-4)) << "pushed on";
  // Its effective mass there is well under the node's: the collision takes most of its speed.
  EXPECT_LT(along, btScalar(0.9));
}

TEST(ToolReaction, ANodeThatCannotGiveWayStopsTheTool) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, 2, btVector3(0, -3, 0));
  applyNodeReaction(*tool, btVector3(0, btScalar(-0.02), 0), btVector3(0, btScalar(-0.001), 0), 0, 1 / kStep, btVector3(0, 0, 0));
  EXPECT_NEAR(tool->getLinearVelocity().y(), 0, 1e-5);
}

// Where the tool stands after the step it now takes, as Bullet integrates it.
btTransform endOfStep(const btRigidBody& tool) {
  btTransform end;
  btTransformUtil::integrateTransform(tool.getCenterOfMassTransform(), tool.getLinearVelocity(),
                                      tool.getAngularVelocity(), kStep, end);
  return end;
}

// Where a body stands at fraction t of a step from start to end, read as the ground truth reads a
// step: the origin along the chord, the turn by Bullet's slerp.
btTransform between(const btTransform& start, const btTransform& end, btScalar t) {
  return btTransform(start.getRotation().slerp(end.getRotation(), t), start.getOrigin().lerp(end.getOrigin(), t));
}

// How far the node comes into the plate (m, 0 when it stays outside) over the step the tool then
// takes, as Bullet integrates it, read between its two poses at 200 instants.
double deepestOnTheWay(const btRigidBody& tool, const ToolModel& plate, const Vec3& node) {
  const btTransform start = tool.getCenterOfMassTransform();
  const btTransform end = endOfStep(tool);
  double deepest = 0;
  for (int k = 1; k <= 200; ++k) {
    const btVector3 seen = between(start, end, btScalar(k) / 200).invXform(toBt(node));
    deepest = std::max(deepest, -double(outsideDistance(plate.planes, toVec3(seen))));
  }
  return deepest;
}

// A plate turning 60° a step about its long axis while it slides along it: at the start its point
// at a pinned node 1 cm above it moves along the plate, not towards the node, and at the end of
// the step the node is 3 cm below it, outside. On its way the plate's face sweeps through the node;
// the stop must see that and hold the plate on the node's side.
TEST(ToolReaction, APinnedNodeStopsATurningToolThatWouldSweepThroughIt) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, 2, btVector3(0, 0, 3));
  const btScalar spin = btScalar(kPi / 3) / kStep;
  tool->setAngularVelocity(btVector3(spin, 0, 0));
  const ToolModel plate = buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), ToolModelSettings{});
  const Vec3 node{0.1, 0.02, 0};
  stopShortOfPinnedNode(*tool, plate, Pose{}, node, 1 / kStep, false);

  EXPECT_LT(deepestOnTheWay(*tool, plate, node), 1e-4);
  EXPECT_GT(endOfStep(*tool).invXform(toBt(node)).y(), btScalar(0.01 - 1e-4)) << "the node ends on the far side";
}

// Whether the plate (half extents 0.2, 0.01, 0.2 about its origin) carries the node through it
// over the step the tool then takes, as Bullet integrates it, by the ground truth's rule
// (eval/GroundTruth.h): the node ends on the other side of the plate's mid-plane, and both the
// chord in the plate's frame and the arc between the plate's two poses (200 instants, the node
// still) take it across within the plate's outline; or it ends inside. Both by more than the
// ground truth's tolerance: a stop may leave the plate touching the node.
bool carriedThrough(const btRigidBody& tool, const Vec3& node) {
  const btTransform start = tool.getCenterOfMassTransform();
  const btTransform end = endOfStep(tool);
  const auto acrossWithin = [](const btVector3& from, const btVector3& to) {
    if ((from.y() > 0) == (to.y() > 0)) return false;
    const btVector3 across = from.lerp(to, from.y() / (from.y() - to.y()));
    return std::abs(across.x()) < 0.2 - kTolerance && std::abs(across.z()) < 0.2 - kTolerance;
  };
  const btVector3 first = start.invXform(toBt(node));
  const btVector3 last = end.invXform(toBt(node));
  if (std::abs(last.x()) < 0.2 && std::abs(last.y()) < 0.01 - kTolerance && std::abs(last.z()) < 0.2) return true;
  if (!acrossWithin(first, last)) return false;
  btVector3 previous = first;
  for (int k = 1; k <= 200; ++k) {
    const btVector3 seen = between(start, end, btScalar(k) / 200).invXform(toBt(node));
    if (acrossWithin(previous, seen)) return true;
    previous = seen;
  }
  return false;
}

// Past 45° a step Bullet turns a body by less than its angular velocity says, and not in
// proportion to the time: a part of the step integrated alone does not lie on the arc between the
// step's two poses. A plate with 150° of turn a step in its angular velocity, rising and sliding
// under a grid of pinned nodes, is stopped short of passing through each.
TEST(ToolReaction, PinnedNodesStopASpinningToolOnTheArcBetweenItsPoses) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  const ToolModel plate = buildToolModel(makeBoxMesh({0.2, 0.01, 0.2}), ToolModelSettings{});
  const btScalar spin = btScalar(150 * kPi / 180) / kStep;
  int through = 0;
  for (int row = 0; row < 6; ++row) {
    for (int column = 0; column < 9; ++column) {
      const Vec3 node{-0.2 + 0.05 * column, 0.02 + 0.03 * row, 0.05};
      auto tool = movingBox(shape, 2, btVector3(0, 3, 3));
      tool->setAngularVelocity(btVector3(spin, 0, btScalar(0.3) * spin));
      const auto forEachPinned = [&](const auto& visit) { visit(plate, Pose{}, node); };
      DynamicBody dynamic(*tool);
      stopShortOfPinnedNodes(dynamic, forEachPinned, 1 / kStep, false);
      if (carriedThrough(*tool, node)) {
        ++through;
        ADD_FAILURE() << "the plate passed through the node at " << node.x << ", " << node.y << ", " << node.z;
      }
    }
  }
  EXPECT_EQ(through, 0);
}

TEST(ToolReaction, ANodeLeavingFasterThanTheToolTakesNothing) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, 1, btVector3(0, 0, 0));
  const btVector3 displacement(0, btScalar(-0.001), 0);
  const btScalar impulse = applyNodeReaction(*tool, btVector3(0, btScalar(-0.02), 0), displacement, 1, 1 / kStep,
                                             btVector3(0, -5, 0));
  EXPECT_EQ(impulse, 0);
  EXPECT_EQ(tool->getLinearVelocity().length2(), 0);
}

TEST(ToolReaction, NoMoveOrABadMassIsNoReaction) {
  btBoxShape shape(btVector3(0.2f, 0.01f, 0.2f));
  auto tool = movingBox(shape, 1, btVector3(0, -1, 0));
  EXPECT_EQ(applyNodeReaction(*tool, btVector3(0, 0, 0), btVector3(0, 0, 0), 1, 1 / kStep, btVector3(0, 0, 0)), 0);
  EXPECT_EQ(applyNodeReaction(*tool, btVector3(0, 0, 0), btVector3(0, -1, 0), -1, 1 / kStep, btVector3(0, 0, 0)), 0);
  EXPECT_EQ(tool->getLinearVelocity(), btVector3(0, -1, 0));
}

}  // namespace
}  // namespace thintool::detail
