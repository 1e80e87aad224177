// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The stability suite: every stiff and extreme case of scenes/StressCases.h held to its
// expectation, the paper's force response shown unstable where the default is not, broken soft
// meshes skipped and counted without harm to the world, and a body's force kick bounded in the
// step after a guarded one.

#include "SoftWorld.h"
#include "StressCases.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <cstdio>
#include <vector>

namespace thintool::scenes {
namespace {

class StressCaseTest : public ::testing::TestWithParam<std::size_t> {};

TEST_P(StressCaseTest, MeetsItsExpectation) {
  const StressCase c = stressCases()[GetParam()];
  const StressOutcome outcome = runStressCase(c);
  std::string why;
  EXPECT_TRUE(meets(outcome, c.expectation, &why)) << c.group << ": " << c.name << ": " << why;
}

std::string caseName(const ::testing::TestParamInfo<std::size_t>& info) {
  const StressCase c = stressCases()[info.param];
  std::string name = std::to_string(info.param) + "_";
  for (char ch : c.group + " " + c.name) {
    if (std::isalnum(static_cast<unsigned char>(ch))) name += ch;
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Cases, StressCaseTest, ::testing::Range<std::size_t>(0, stressCases().size()), caseName);

// The default response's stiffness cases expect containment, which StressCaseTest asserts case by
// case; the paper's expect only finite nodes. Here, that the paper's explicit force does fail
// somewhere: the first of its cases that lets a node through or into the tool answers that, so
// the cases after it (the slowest, at 1/10,000 s) need not run again.
TEST(Stability, ThePapersForceResponseFailsWhereTheDefaultHolds) {
  int paperCases = 0, defaultContained = 0;
  bool paperFailed = false;
  for (const StressCase& c : stressCases()) {
    if (c.group != "stiffness" || c.scene.toolOptions.force.enabled) continue;
    if (c.scene.toolOptions.response.kind != ResponseKind::PaperForce) {
      defaultContained += c.expectation == Expectation::Contained ? 1 : 0;
      continue;
    }
    ++paperCases;
    if (!meets(runStressCase(c), Expectation::Contained)) {
      paperFailed = true;
      break;
    }
  }
  EXPECT_GT(defaultContained, 0) << "the default response's stiffness cases expect containment";
  EXPECT_GT(paperCases, 0);
  EXPECT_TRUE(paperFailed) << "an explicit f = k·t has a stiffness and step it cannot hold";
}

TEST(Stability, ANonFiniteToolPoseIsSkippedCountedAndTheTissueStaysHeld) {
  for (const StressCase& c : stressCases()) {
    if (c.name.find("NaN") == std::string::npos) continue;
    const StressOutcome outcome = runStressCase(c);
    EXPECT_GT(outcome.invalidPosePairs, 0);
    EXPECT_TRUE(meets(outcome, Expectation::Contained));
    return;
  }
  FAIL() << "no NaN-pose case";
}

// A sheet of 9×9 nodes of 1 kg, 0.1 m apart at height 1, pinned at its corners; links along its
// rows and columns, two faces a cell.
constexpr int kSheetSide = 9;

int sheetNode(int i, int j) { return i * kSheetSide + j; }

std::unique_ptr<btSoftBody> pinnedSheet(btSoftBodyWorldInfo& worldInfo) {
  std::vector<btVector3> positions;
  std::vector<btScalar> masses;
  for (int i = 0; i < kSheetSide; ++i) {
    for (int j = 0; j < kSheetSide; ++j) {
      positions.emplace_back(btScalar(-0.4 + 0.1 * i), 1, btScalar(-0.4 + 0.1 * j));
      masses.push_back(1);
    }
  }
  auto sheet = std::make_unique<btSoftBody>(&worldInfo, static_cast<int>(positions.size()), positions.data(),
                                            masses.data());
  for (int i = 0; i + 1 < kSheetSide; ++i) {
    for (int j = 0; j + 1 < kSheetSide; ++j) {
      sheet->appendFace(sheetNode(i, j), sheetNode(i + 1, j), sheetNode(i + 1, j + 1));
      sheet->appendFace(sheetNode(i, j), sheetNode(i + 1, j + 1), sheetNode(i, j + 1));
      sheet->appendLink(sheetNode(i, j), sheetNode(i + 1, j));
      sheet->appendLink(sheetNode(i, j), sheetNode(i, j + 1));
    }
  }
  const int last = kSheetSide - 1;
  for (int corner : {sheetNode(0, 0), sheetNode(0, last), sheetNode(last, 0), sheetNode(last, last)}) {
    sheet->setMass(corner, 0);
  }
  sheet->getCollisionShape()->setMargin(btScalar(0.01));
  return sheet;
}

// A kinematic plate 0.3 m square and 0.02 m thick, level, centred over the sheet at a height.
struct KinematicPlate {
  btBoxShape shape{btVector3(0.15, 0.01, 0.15)};
  btDefaultMotionState motion;
  btRigidBody body;

  explicit KinematicPlate(btScalar height)
      : motion(btTransform(btQuaternion::getIdentity(), btVector3(0, height, 0))),
        body(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &shape)) {
    body.setCollisionFlags(body.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  }
  void moveTo(btScalar height) {
    motion.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, height, 0)));
  }
};

// A pinned sheet with broken faces under the plate: one of zero area (its corners in a line),
// one given twice, one wound the other way. The plate presses the sheet's middle. (A node whose
// position is NaN cannot be tested here: Bullet's soft body bounds become NaN and its broadphase
// never pairs the body with anything; DetectionTest covers such faces in the core.)
TEST(Stability, BrokenSoftFacesAreSkippedAndCounted) {
  SoftWorld soft(btVector3(0, 0, 0));
  btSoftRigidDynamicsWorld& world = soft.world;

  std::unique_ptr<btSoftBody> made = pinnedSheet(world.getWorldInfo());
  btSoftBody& sheet = *made;
  const int nodeCount = sheet.m_nodes.size();
  sheet.appendFace(sheetNode(3, 3), sheetNode(4, 4), sheetNode(5, 5));  // three nodes in a line
  sheet.appendFace(sheetNode(3, 3), sheetNode(4, 3), sheetNode(4, 4));
  sheet.appendFace(sheetNode(3, 3), sheetNode(3, 4), sheetNode(4, 4));
  world.addSoftBody(&sheet);

  KinematicPlate plate(1.1);
  world.addRigidBody(&plate.body);
  Tool& tool = addTool(world, plate.body, ToolOptions{});

  long skipped = 0;
  Index contacts = 0;
  for (int step = 1; step <= 30; ++step) {
    plate.moveTo(btScalar(1.1 - 0.01 * step));
    world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
    const ToolStepReport& report = tool.report();
    skipped += long(report.diagnostics.detection.skippedFaces);
    contacts += static_cast<Index>(report.contacts.size());
    for (const ToolContact& c : report.contacts) {
      ASSERT_TRUE(std::isfinite(c.contact.normal.x) && std::isfinite(c.contact.point.y) && std::isfinite(c.contact.depth));
    }
  }
  EXPECT_GT(skipped, 0) << "the zero-area face is left out, and counted";
  EXPECT_GT(contacts, 0u) << "the rest of the sheet is still handled";
  for (int i = 0; i < nodeCount; ++i) {
    const btVector3& x = sheet.m_nodes[i].m_x;
    ASSERT_TRUE(std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z())) << "node " << i;
    if (std::abs(x.x()) < 0.1 && std::abs(x.z()) < 0.1) {
      EXPECT_LT(x.y(), 0.8 - 0.01) << "node " << i << " stays under the plate";
    }
  }
  removeTool(world, plate.body);
  world.removeRigidBody(&plate.body);
  world.removeSoftBody(&sheet);
}

// A pinned sheet in a world without gravity, and a kinematic plate registered as a tool with the
// given energy guard, which presses the sheet step after step so that the guard runs on it.
struct PressedSheet {
  static constexpr btScalar kStep = btScalar(1) / 60;
  SoftWorld soft{btVector3(0, 0, 0)};
  std::unique_ptr<btSoftBody> sheet = pinnedSheet(soft.world.getWorldInfo());
  KinematicPlate plate{btScalar(1.05)};
  Tool* tool = nullptr;

  explicit PressedSheet(const EnergyGuardSettings& guard) {
    soft.world.addSoftBody(sheet.get());
    soft.world.addRigidBody(&plate.body);
    ToolOptions options;
    options.energyGuard = guard;
    tool = &addTool(soft.world, plate.body, options);
  }
  ~PressedSheet() {
    removeTool(soft.world, plate.body);
    soft.world.removeRigidBody(&plate.body);
    soft.world.removeSoftBody(sheet.get());
  }
  // The plate 5 mm lower each step.
  void step(int step) {
    plate.moveTo(btScalar(1.05 - 0.005 * step));
    soft.world.stepSimulation(kStep, 1, kStep);
  }
};

// After 20 steps of the pressed sheet one free node far from the plate gets a force worth 1000 m/s
// in a step (the kind of kick Bullet's pressure gives a body squeezed flat). Returns how far that
// node moves in the step, and leaves in userBound what the world's
// btSoftBodyWorldInfo::m_maxDisplacement is after it.
double kickedNodeMove(const EnergyGuardSettings& guard, btScalar& userBound) {
  PressedSheet pressed(guard);
  pressed.soft.world.getWorldInfo().m_maxDisplacement = 500;
  btSoftBody& sheet = *pressed.sheet;
  const int kicked = sheetNode(1, 1);
  btVector3 before(0, 0, 0);
  for (int step = 1; step <= 21; ++step) {
    if (step == 21) {
      before = sheet.m_nodes[kicked].m_x;
      sheet.addForce(btVector3(0, 1000 / PressedSheet::kStep, 0), kicked);  // 1 kg: 1000 m/s in one step
    }
    pressed.step(step);
  }
  userBound = pressed.soft.world.getWorldInfo().m_maxDisplacement;
  return double((sheet.m_nodes[kicked].m_x - before).length());
}

TEST(Stability, AForceKickInTheStepAfterAGuardedOneIsBounded) {
  EnergyGuardSettings guard;
  btScalar userBound = 0;
  const double bounded = kickedNodeMove(guard, userBound);
  EXPECT_EQ(userBound, btScalar(500)) << "the world's own bound is the user's again after the step";
  guard.boundForcesNextStep = false;
  const double unbounded = kickedNodeMove(guard, userBound);
  EXPECT_EQ(userBound, btScalar(500));
  std::printf("the kicked node moved %.3f m with the bound, %.3f m without\n", bounded, unbounded);
  // The bound: twice the fastest node or tool corner, at least 1 m/s, in a step, per axis; the
  // plate goes 0.3 m/s and the sheet's nodes about as fast, so a few centimetres.
  EXPECT_LT(bounded, 0.1) << "held to the speeds in a step";
  EXPECT_GT(unbounded, 50 * bounded) << "without the bound the kick goes through, as in stock Bullet";
}

// After 20 steps of the pressed sheet one free node far from the plate is lifted 0.5 m off the
// sheet, at rest, so that Bullet's solve snaps its stretched links back within the step, far
// faster than the plate or any node moves. Returns the fastest node's move over a step, as a speed,
// over that step and the 9 after it, and how many moves the guard shortened.
struct SnapBack {
  double fastest = 0;  // m/s
  Index shortened = 0;
};

SnapBack snapBack(const EnergyGuardSettings& guard) {
  PressedSheet pressed(guard);
  btSoftBody& sheet = *pressed.sheet;
  SnapBack result;
  std::vector<btVector3> before(static_cast<std::size_t>(sheet.m_nodes.size()));
  for (int step = 1; step <= 30; ++step) {
    if (step == 21) {
      btSoftBody::Node& lifted = sheet.m_nodes[sheetNode(1, 1)];
      lifted.m_x += btVector3(0, btScalar(0.5), 0);
      lifted.m_v = btVector3(0, 0, 0);
    }
    for (int i = 0; i < sheet.m_nodes.size(); ++i) before[static_cast<std::size_t>(i)] = sheet.m_nodes[i].m_x;
    pressed.step(step);
    if (step < 21) continue;
    result.shortened += pressed.tool->report().diagnostics.lastWord.movesShortened;
    for (int i = 0; i < sheet.m_nodes.size(); ++i) {
      const double move = double((sheet.m_nodes[i].m_x - before[static_cast<std::size_t>(i)]).length());
      result.fastest = std::max(result.fastest, move / double(PressedSheet::kStep));
    }
  }
  return result;
}

TEST(Stability, ANodeTheSolveSnapsBackMovesNoFasterThanTheGuardAllowsStepAfterStep) {
  EnergyGuardSettings guard;
  const SnapBack guarded = snapBack(guard);
  guard.enabled = false;
  const SnapBack free = snapBack(guard);
  std::printf("the fastest node after the lift: %.2f m/s guarded (%d moves shortened), %.2f m/s without the guard\n",
              guarded.fastest, int(guarded.shortened), free.fastest);
  // The bound: speedFactor (2) times the faster of 1 m/s and the plate's 0.3 m/s, or the fastest
  // node as predicted before the solve if that is faster; that is the guard's own earlier bound,
  // which must not grow by the factor again step after step while the links keep pulling. After the
  // solve the last word may push a node out of the plate's way, at the plate's 0.3 m/s.
  EXPECT_GT(guarded.shortened, 0);
  EXPECT_LE(guarded.fastest, 2.0 + 0.3) << "no node's move in a step beyond the bound, in any of the ten steps";
  EXPECT_GT(free.fastest, 5 * guarded.fastest) << "without the guard the links snap the node back at once";
}

// The same kick to a sheet squeezed between two still plates, a grasp: the bound is the sheet's
// extent in a step (the holds on both sides take back what a squeezed pressure body's kick
// gives), not the speeds, which a single plate gets.
TEST(Stability, InAGraspTheForceKickIsBoundedByTheBodysExtent) {
  SoftWorld soft(btVector3(0, 0, 0));
  btSoftRigidDynamicsWorld& world = soft.world;
  std::unique_ptr<btSoftBody> made = pinnedSheet(world.getWorldInfo());
  btSoftBody& sheet = *made;
  world.addSoftBody(&sheet);
  // Each plate's face 5 mm from the sheet, inside its 10 mm skin: both push every step.
  KinematicPlate above(btScalar(1.015));
  KinematicPlate below(btScalar(0.985));
  for (KinematicPlate* plate : {&above, &below}) {
    world.addRigidBody(&plate->body);
    addTool(world, plate->body);
  }
  const btScalar dt = btScalar(1) / 60;
  const int kicked = sheetNode(1, 1);
  btVector3 before(0, 0, 0);
  for (int step = 1; step <= 21; ++step) {
    if (step == 21) {
      before = sheet.m_nodes[kicked].m_x;
      sheet.addForce(btVector3(1000 / dt, 0, 0), kicked);  // along the plates, which hold it across
    }
    world.stepSimulation(dt, 1, dt);
  }
  const double moved = double((sheet.m_nodes[kicked].m_x - before).length());
  std::printf("the kicked node of the squeezed sheet moved %.3f m\n", moved);
  EXPECT_GT(moved, 0.1) << "a grasp's bound is the body's extent, not the speeds";
  EXPECT_LT(moved, 0.8 * std::sqrt(2.0)) << "held to the body's extent (0.8·√2 m) in a step";
  for (KinematicPlate* plate : {&above, &below}) {
    removeTool(world, plate->body);
    world.removeRigidBody(&plate->body);
  }
  world.removeSoftBody(&sheet);
}

}  // namespace
}  // namespace thintool::scenes
