// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A robot's two-finger gripper grasping a soft body, in Bullet's btSoftMultiBodyDynamicsWorld or
/// its deformable world (btDeformableMultiBodyDynamicsWorld, the body a mass-spring one there): a
/// Featherstone multibody whose fixed base carries a lift (a prismatic joint up) and on it two
/// fingers (prismatic joints across), each joint driven by a velocity motor of bounded force, as a
/// robot's position-controlled joints are. The fingers close on a tetrahedral cube or cable lying on
/// the ground, lift it, hold it still and let it go. Stock Bullet meets the fingers with its own
/// soft–multibody contact; ThinTool registers each finger link as a tool, with friction.

#include "WorldKind.h"

#include <array>
#include <functional>
#include <string>

class btCollisionWorld;

namespace thintool {
class Tool;
}

namespace thintool::scenes {

enum class GraspedBody { Cube, Cable };
const char* graspedBodyName(GraspedBody body);

struct GripperSettings {
  GraspedBody body = GraspedBody::Cube;
  bool thinTool = true;            ///< false: stock Bullet's configuration and soft-body solver
  /// SoftMultiBody (PyBullet's soft world) or Deformable: there the body is a mass-spring body
  /// whose springs are the tetrahedra's links (deformableSpringFor, at the classic material's kLST),
  /// and the fingers meet Bullet's deformable contacts, with ThinTool's last word after its solve.
  WorldKind world = WorldKind::SoftMultiBody;
  /// Deformable world only: Bullet's own contacts between the body's faces and the fingers
  /// (SDF_MDF). Off, the fingers meet the body through ThinTool's last word alone (and stock
  /// Bullet's not at all).
  bool bulletFingerContacts = true;
  /// Deformable world only, with ThinTool: the fingers' node contacts in Bullet's solve come from
  /// ThinTool's swept detection (BulletSettings::deformableNodeContacts); false keeps Bullet's.
  bool thinToolNodeContacts = true;
  double timeStep = 1.0 / 240;     ///< s
  double gripForce = 50;           ///< N, each finger motor's largest force
  double squeeze = 0.01;           ///< m, how far each finger is driven into the body
  double liftHeight = 0.3;         ///< m
  double bodyMass = 0.5;           ///< kg
  /// The body's kDF: with the fingers' friction (Bullet's default 0.5), the coefficient of
  /// Bullet's contacts and of ThinTool's friction with the fingers (kDF × 0.5).
  double bodyFriction = 0.5;
  /// Called after every step with the world, its soft bodies, the fingers' tools (null with stock
  /// Bullet) and the time (s): a viewer's frame, say. Returning false ends the run there, and the
  /// run's figures cover the steps taken (those of a phase not reached stay 0).
  std::function<bool(const btCollisionWorld&, const btAlignedObjectArray<btSoftBody*>&, const std::array<Tool*, 2>&,
                     double)>
      observer;
};

/// What the grasp did. Phases: settle 0.5 s, close 1.5 s, lift liftHeight at 0.2 m/s, hold 2 s,
/// open 1 s. The load columns are means over the hold's last second, where the body hangs still.
struct GripperRun {
  double rise = 0;             ///< the body's mean node height at the end of the hold, less at rest (m)
  /// The same for the nodes between the fingers' front and back ends when the lift began: the
  /// part they hold, where a long body's ends may hang to the ground (m).
  double heldRise = 0;
  double lift = 0;             ///< the fingers' rise over the same time (m)
  double slip = 0;             ///< how far the body sank against the fingers during the hold (m)
  double afterRelease = 0;     ///< the body's mean height at the end, less at rest (m)
  int crossed = 0;             ///< nodes that passed through a finger (eval ground truth)
  double deepest = 0;          ///< deepest a node or face centroid lay inside a finger after a step (m)
  int piercedSteps = 0;        ///< steps that ended with a soft face deeper than 0.1 mm in a finger
  double grip = 0;             ///< the finger motors' mean squeeze (N)
  double liftLoad = 0;         ///< what the lift motor carries beyond the gripper's own weight (N)
  double bodyLoad = 0;         ///< what the body's momentum says the fingers carry: m g + dp/dt (N)
  /// ThinTool only: what the fingers' reports say they carry (N), −Σ reaction·y: the impulses
  /// ThinTool applied to them. In the deformable world Bullet's contacts apply theirs, and the
  /// reports' holdWrench holds those with the last word's: −Σ holdWrench·y.
  double reportedLoad = 0;
  /// ThinTool only: what ThinTool itself applied to the fingers, −Σ reaction·y (N): in the classic
  /// worlds reportedLoad, in the deformable world the last word's part of it.
  double appliedLoad = 0;
  bool finite = true;          ///< every node and joint finite at every step
  double wallMilliseconds = 0; ///< world steps, per step
};

GripperRun runGripper(const GripperSettings& settings);

}  // namespace thintool::scenes
