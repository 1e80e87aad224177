// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// A dynamic tool's body as the tissue's reactions see it: a dynamic btRigidBody, or a link of a
// Featherstone btMultiBody that its joints or its free base let move. A rigid body's row (its speed
// and effective mass at a point along a direction, rotation included, as the normal row of a
// sequential-impulse solver such as Box2D's) is ToolReaction.cpp's; a link's comes from the
// multibody's contact Jacobian J and its articulated mass matrix M, 1 / (J M⁻¹ Jᵀ), and an impulse
// changes the joint velocities by M⁻¹ Jᵀ, as Bullet's own multibody contacts do
// (btMultiBodyConstraint). Bullet
// refreshes the factors of M in each step's forward dynamics; in the collision pass they are the
// previous step's, one step stale, and before a multibody's first step they are zero, which makes
// the link immovable (no exchange) for that step.

#include <LinearMath/btAlignedObjectArray.h>
#include <LinearMath/btMatrix3x3.h>
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

class btCollisionObject;
class btMultiBodyLinkCollider;
class btRigidBody;

namespace thintool::detail {

/// The impulses applied to a dynamic tool over a step: their sum (N s, world) and the sum of their
/// moments about the world's origin (N m s).
struct AppliedImpulse {
  btVector3 linear{0, 0, 0};
  btVector3 angular{0, 0, 0};
  void add(const btVector3& impulse, const btVector3& point) {
    linear += impulse;
    angular += point.cross(impulse);
  }
};

/// Room for a multibody's Jacobian row and its solve, kept by the tool between steps so that the
/// reactions allocate nothing once it has grown to the multibody's size.
struct JacobianScratch {
  btAlignedObjectArray<btScalar> jacobian;        // J, 6 + degrees of freedom
  btAlignedObjectArray<btScalar> velocityChange;  // M⁻¹ Jᵀ, per unit impulse
  btAlignedObjectArray<btScalar> reals;
  btAlignedObjectArray<btVector3> vectors;
  btAlignedObjectArray<btMatrix3x3> matrices;
};

class DynamicBody {
 public:
  DynamicBody() = default;
  explicit DynamicBody(btRigidBody& body, AppliedImpulse* applied = nullptr) : m_rigid(&body), m_applied(applied) {}

  /// body's view, or an empty one when the tissue cannot move it: a static or kinematic
  /// btRigidBody, a multibody's fixed or kinematic base, a collider flagged static or kinematic,
  /// a plain btCollisionObject. Every impulse applied through the view is added to applied.
  static DynamicBody of(btCollisionObject& body, JacobianScratch& scratch, AppliedImpulse& applied);

  explicit operator bool() const { return m_rigid != nullptr || m_link != nullptr; }
  /// The body when it is a btRigidBody; null for a multibody link.
  btRigidBody* rigid() const { return m_rigid; }
  /// Where the impulses applied to the body are summed; null when nowhere.
  AppliedImpulse* applied() const { return m_applied; }

  /// A multibody link at point (m, world) along the unit vector direction: its speed there (m/s)
  /// and the inverse of its effective mass there (1/kg; 0 where it cannot move along direction).
  /// A rigid body's reactions use its own row (ToolReaction.cpp); for it, as for an empty view,
  /// both are 0.
  struct Row {
    btScalar speed = 0;
    btScalar inverseMass = 0;
  };
  /// Also readies applyAlongRow for this point and direction.
  Row row(const btVector3& point, const btVector3& direction);
  /// Applies impulse (N s) to a link along the direction of the last row, at its point.
  void applyAlongRow(btScalar impulse);
  /// Applies impulse (N s, world) at point (m, world).
  void applyImpulse(const btVector3& impulse, const btVector3& point);
  /// A multibody link's pose after timeStep (s) at its present velocities, integrated as Bullet
  /// integrates a rigid body's; false for a rigid body (Bullet predicts its own) or an empty view.
  bool predictLinkPose(btScalar timeStep, btTransform& outPose);
  /// Wakes the body (and a multibody's links) so that Bullet integrates what was applied.
  void activate();
  /// Whether every joint velocity of a link's multibody is finite (true for any other view).
  bool linkVelocitiesFinite() const;

 private:
  btRigidBody* m_rigid = nullptr;
  btMultiBodyLinkCollider* m_link = nullptr;
  JacobianScratch* m_scratch = nullptr;
  AppliedImpulse* m_applied = nullptr;
  btVector3 m_rowPoint{0, 0, 0};
  btVector3 m_rowDirection{0, 0, 0};
};

}  // namespace thintool::detail
