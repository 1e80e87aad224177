// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

#include <memory>
#include <vector>

class btBroadphaseInterface;
class btCollisionConfiguration;
class btConstraintSolver;
class btDeformableLagrangianForce;
class btDeformableMultiBodyDynamicsWorld;
class btDiscreteDynamicsWorld;
class btMultiBodyDynamicsWorld;
class btDispatcher;
class btSoftBody;
class btSoftBodySolver;
class btSoftMultiBodyDynamicsWorld;
class btSoftRigidDynamicsWorld;
class btVector3;
template <typename T>
class btAlignedObjectArray;
struct btSoftBodyWorldInfo;

namespace thintool {
class CollisionConfiguration;
}  // namespace thintool

namespace thintool::scenes {

/// The Bullet world a scene is built in.
enum class WorldKind {
  SoftRigid,      ///< btSoftRigidDynamicsWorld, with btSequentialImpulseConstraintSolver
  SoftMultiBody,  ///< btSoftMultiBodyDynamicsWorld, with btMultiBodyConstraintSolver (PyBullet's soft world)
  /// btDeformableMultiBodyDynamicsWorld, with btDeformableMultiBodyConstraintSolver; each soft body
  /// is a mass-spring body (btDeformableMassSpringForce, kDeformableSpring) under gravity.
  Deformable,
};

/// The deformable kind's springs: elastic stiffness (N/m) and damping (N·s/m) of
/// btDeformableMassSpringForce. The scenes' 1 kg ball keeps its shape under gravity with these at
/// 1/60 s; with 30 N/m (Bullet's cloth examples) it folds flat, and from 150 N/m its solve diverges.
inline constexpr double kDeformableSpring = 100;
inline constexpr double kDeformableSpringDamping = 1;

/// Springs for a ball of any resolution and mass in the deformable world: each node's spring
/// frequency that of the scenes' 1 kg ball of 66 nodes at kDeformableSpring.
double ballSpringFor(const btSoftBody& body);

/// Springs for a body of any mesh, mass and step in the deformable world: a quarter as stiff, for
/// its mass per node and the step (s), as the scenes' 1 kg ball is at kDeformableSpring and 1/60 s,
/// times stiffness (0 to 1, the classic material's kLST). Bullet's deformable solve diverges on
/// stiffer springs than the step allows, so the generated scenes tie the springs to it.
double deformableSpringFor(const btSoftBody& body, double stiffness, double step);

/// The soft-body solver a world of the kind takes: ThinTool's for the configuration when thinTool
/// is given (SoftBodySolver, or DeformableBodySolver in the deformable world), else Bullet's own.
std::unique_ptr<btSoftBodySolver> softSolverFor(WorldKind kind, CollisionConfiguration* thinTool);

/// A world of any kind with its constraint solver, and the soft-body calls the kinds do not share.
/// Destroy it before the parts it was made with.
class SoftWorldOfKind {
 public:
  /// softSolver: one softSolverFor(kind, ...) made.
  SoftWorldOfKind(WorldKind kind, btDispatcher& dispatcher, btBroadphaseInterface& broadphase,
                  btCollisionConfiguration& configuration, btSoftBodySolver& softSolver);
  ~SoftWorldOfKind();
  SoftWorldOfKind(const SoftWorldOfKind&) = delete;
  SoftWorldOfKind& operator=(const SoftWorldOfKind&) = delete;

  btDiscreteDynamicsWorld& world() { return *m_world; }
  /// Null for the other kinds.
  btSoftRigidDynamicsWorld* softRigid() { return m_softRigid; }
  /// The soft multibody or the deformable world, which take multibodies; null for the other kind.
  btMultiBodyDynamicsWorld* multiBody();
  const btAlignedObjectArray<btSoftBody*>& softBodies() const;
  btSoftBodyWorldInfo& worldInfo();
  /// The world's gravity, its soft bodies' (btSoftBodyWorldInfo::m_gravity) and, in the deformable
  /// world, that of the gravity forces it keeps.
  void setGravity(const btVector3& gravity);
  /// In the deformable world, the body takes Bullet's deformable rigid contacts on its faces, against
  /// rigid bodies and multibody links (SDF_RD, SDF_RDF, SDF_MDF), and gets springs (elastic
  /// stiffness springStiffness, N/m) and gravity, which the world keeps.
  void addSoftBody(btSoftBody* body, double springStiffness = kDeformableSpring);
  void removeSoftBody(btSoftBody* body);

 private:
  std::unique_ptr<btConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  btSoftRigidDynamicsWorld* m_softRigid = nullptr;          // m_world, when of that kind
  btSoftMultiBodyDynamicsWorld* m_softMultiBody = nullptr;  // m_world, when of that kind
  btDeformableMultiBodyDynamicsWorld* m_deformable = nullptr;  // m_world, when of that kind
  std::vector<std::unique_ptr<btDeformableLagrangianForce>> m_forces;
};

}  // namespace thintool::scenes
