// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

#include <memory>

class btBroadphaseInterface;
class btCollisionConfiguration;
class btConstraintSolver;
class btDiscreteDynamicsWorld;
class btDispatcher;
class btSoftBody;
class btSoftBodySolver;
class btSoftMultiBodyDynamicsWorld;
class btSoftRigidDynamicsWorld;
struct btSoftBodyWorldInfo;

namespace thintool::scenes {

/// The Bullet world a scene is built in.
enum class WorldKind {
  SoftRigid,      ///< btSoftRigidDynamicsWorld, with btSequentialImpulseConstraintSolver
  SoftMultiBody,  ///< btSoftMultiBodyDynamicsWorld, with btMultiBodyConstraintSolver (PyBullet's soft world)
};

/// A world of either kind with its constraint solver, and the soft-body calls the two kinds do not
/// share. Destroy it before the parts it was made with.
class SoftWorldOfKind {
 public:
  SoftWorldOfKind(WorldKind kind, btDispatcher& dispatcher, btBroadphaseInterface& broadphase,
                  btCollisionConfiguration& configuration, btSoftBodySolver& softSolver);
  ~SoftWorldOfKind();
  SoftWorldOfKind(const SoftWorldOfKind&) = delete;
  SoftWorldOfKind& operator=(const SoftWorldOfKind&) = delete;

  btDiscreteDynamicsWorld& world() { return *m_world; }
  /// Null for the other kind.
  btSoftRigidDynamicsWorld* softRigid() { return m_softRigid; }
  btSoftBodyWorldInfo& worldInfo();
  void addSoftBody(btSoftBody* body);
  void removeSoftBody(btSoftBody* body);

 private:
  std::unique_ptr<btConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  btSoftRigidDynamicsWorld* m_softRigid = nullptr;          // m_world, when of that kind
  btSoftMultiBodyDynamicsWorld* m_softMultiBody = nullptr;  // m_world, when of that kind
};

}  // namespace thintool::scenes
