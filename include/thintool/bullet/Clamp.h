// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The paper's clamp (§IV.A, Figs. 9, 10, 12): two thin jaws, each a kinematic box registered as
/// a ThinTool tool, hinged on a handle that does not collide, with one degree of freedom that opens
/// and closes them. The caller moves the handle and sets the opening; the jaws follow through their
/// motion states, so a haptic device or a script drives the clamp alike.
///
/// Frame of the handle: the hinge at its origin, the jaws reaching along +x, opening in the x–y
/// plane, symmetrically about y = 0. At opening 0 the jaws' inner faces meet at y = 0.

#include <thintool/bullet/Tool.h>
#include <thintool/bullet/ToolOptions.h>
#include <thintool/core/Api.h>

#include <LinearMath/btTransform.h>

#include <array>
#include <memory>

class btSoftRigidDynamicsWorld;
class btRigidBody;

namespace thintool {

struct ClampSettings {
  std::string name = "clamp";  ///< the jaws are "<name> upper jaw" and "<name> lower jaw"
  Vec3 jawHalfExtents{0.6, 0.01, 0.15};  ///< m: length along x, thickness along y, width along z
  Real maxOpening = kPi / 2;            ///< rad, the largest angle between the jaws (> 0, < π)
  /// Both jaws' options. Friction is on, so that a grasp can lift; the name is set per jaw.
  ToolOptions jawOptions = defaultJawOptions();

  static ToolOptions defaultJawOptions() {
    ToolOptions options;
    // A grasp's own coefficients, not the soft body's: a jaw's grip is the clamp's design.
    options.response.friction.enabled = true;
    options.bullet.frictionFromBodies = false;
    return options;
  }
};

/// What the jaws feel in the latest step (N, world), from each jaw's report: the response's
/// wrench and, in a world whose soft-body solver is a thintool::SoftBodySolver, the load its holds
/// carried (ToolStepReport::holdWrench), which is where a lifted body's weight comes in.
struct ClampForces {
  std::array<Vec3, 2> onJaw;  ///< the tissue's force on the upper and the lower jaw
  Vec3 onBody;                ///< the jaws' resultant on the grasped body: -(onJaw[0] + onJaw[1])
  /// The squeeze: each jaw's force along its own inward normal, averaged over the two (N).
  Real grip = 0;
};

class THINTOOL_API Clamp {
 public:
  /// Adds the handle and the jaws to world (a btSoftRigidDynamicsWorld built on
  /// thintool::CollisionConfiguration) at handlePose, opened by opening radians. Throws
  /// thintool::Error for invalid settings, naming the clamp and the field.
  Clamp(btSoftRigidDynamicsWorld& world, const ClampSettings& settings, const btTransform& handlePose,
        Real opening);
  ~Clamp();
  Clamp(const Clamp&) = delete;
  Clamp& operator=(const Clamp&) = delete;

  /// Moves the handle and sets the opening (clamped to [0, maxOpening]) for the next step.
  void setPose(const btTransform& handlePose, Real opening);
  const btTransform& handlePose() const { return m_handlePose; }
  Real opening() const { return m_opening; }

  /// Jaw 0 is the upper one (+y side of the handle), jaw 1 the lower one.
  Tool& jaw(int i) { return *m_jawTools[i]; }
  btRigidBody& jawBody(int i) { return *m_jawBodies[i]; }
  btRigidBody& handle() { return *m_handle; }
  /// A jaw's pose for a handle pose and opening (the hinge geometry, for callers and tests).
  btTransform jawPose(int i, const btTransform& handlePose, Real opening) const;

  /// Reads both jaws' reports of the latest step.
  ClampForces forces();

 private:
  struct Parts;
  btSoftRigidDynamicsWorld& m_world;
  ClampSettings m_settings;
  std::unique_ptr<Parts> m_parts;
  std::array<btRigidBody*, 2> m_jawBodies{};
  std::array<Tool*, 2> m_jawTools{};
  btRigidBody* m_handle = nullptr;
  btTransform m_handlePose;
  Real m_opening = 0;
};

}  // namespace thintool
