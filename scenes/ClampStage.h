// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The clamp scene of ClampScene.h up to the grasp, for whatever drives the clamp: a script
/// (runClamp) or a haptic device (runClampSession). Not part of the library.

#include "ClampScene.h"
#include "Metrics.h"
#include "SoftWorld.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace thintool::scenes {

// The ground, the settled body, the open clamp at its hinge; then one step at a time, each with
// its sample.
class ClampStage {
 public:
  ClampStage(ClampBody kind, bool friction, double timeStep, double squeeze);
  ~ClampStage();
  ClampStage(const ClampStage&) = delete;
  ClampStage& operator=(const ClampStage&) = delete;

  int stepsOf(double seconds) const;
  double restCentreHeight() const { return m_restCentreHeight; }
  const btTransform& handle() const { return m_handle; }  // where the clamp began, open
  double open() const { return m_clampSettings.maxOpening; }
  double closed() const { return m_closed; }  // the opening that squeezes the body as asked
  Clamp& clamp() { return *m_clamp; }
  const btSoftRigidDynamicsWorld& world() const { return m_soft.world; }
  double bodyMass() const;
  double centreHeight() const;
  double wallMicroseconds() const { return m_wallMicroseconds; }

  // Sets the clamp, steps the world once, and samples it.
  ClampSample step(const btTransform& pose, double opening, const std::string& phase, ClampForces& forces);

 private:
  std::array<ToolBox, 2> boxes();

  double m_timeStep;
  SoftWorld m_soft;
  btBoxShape m_groundShape{btVector3(20, 1, 20)};
  btDefaultMotionState m_groundMotion{btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0))};
  btRigidBody m_ground{btRigidBody::btRigidBodyConstructionInfo(0, &m_groundMotion, &m_groundShape)};
  btSoftBody* m_body = nullptr;
  double m_restCentreHeight = 0;
  ClampSettings m_clampSettings;
  btTransform m_handle;
  std::unique_ptr<Clamp> m_clamp;
  double m_closed = 0;
  std::vector<std::array<int, 3>> m_faces;
  std::array<BoxGroundTruth, 2> m_truths;
  btVector3 m_lastMomentum{0, 0, 0};
  double m_time = 0;
  double m_wallMicroseconds = 0;
};

}  // namespace thintool::scenes
