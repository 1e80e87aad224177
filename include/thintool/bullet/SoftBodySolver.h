// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The last word: a soft-body solver to pass to btSoftRigidDynamicsWorld or
/// btSoftMultiBodyDynamicsWorld where btDefaultSoftBodySolver was.
///
///     thintool::CollisionConfiguration configuration;
///     thintool::SoftBodySolver softBodySolver(configuration);
///     btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &constraintSolver, &configuration,
///                                    &softBodySolver);
///
/// Bullet runs the world's soft-body solver after the collision pass, and the solver moves the
/// nodes again (links, pressure, its own contacts): whatever the collision pass did, the soft
/// solver has the last word on where a node ends the step. This one runs Bullet's own solve
/// unchanged (for a body that tools hold in it or that the last word looks at, Bullet's stages one
/// by one, so as to measure what the holds carried, ToolStepReport::holdWrench, and to survey the
/// body in the solve's last pass over its nodes), then, for every tool of the configuration
/// whose ToolOptions::separation is enabled, puts every soft node and face near the tool back on
/// its side (response/Separation.h) and sets a moved node's velocity along its move to the faster
/// of its own and the tool's (no bounce). A dynamic tool receives the moved nodes' reaction as impulses, unless its force model already
/// reacts on it (ForceSettings::applyToDynamicTool). Soft bodies that ignore the tool
/// (m_collisionDisabledObjects) are left alone. Last, the energy guard (EnergyGuardSettings)
/// bounds the velocities of each soft body a tool's response moved in the step (and, in the solve,
/// its nodes' moves), and, in Bullet's prediction of the next step, what that body's forces add to
/// them. In the prediction of a pose-matched body a tool is at, a frame that Bullet's polar
/// decomposition failed to make a rotation (a flat body folded) is replaced by the nearest rotation
/// before the match (LastWordDiagnostics::poseFramesRepaired). Tool::report() says what the stages
/// did and what they left (ToolDiagnostics::lastWord).

#include <thintool/core/Api.h>

#include <BulletSoftBody/btDefaultSoftBodySolver.h>

#include <memory>

namespace thintool {

class CollisionConfiguration;
namespace detail {
class SoftBodySolverImpl;
}  // namespace detail

class THINTOOL_API SoftBodySolver : public btDefaultSoftBodySolver {
 public:
  /// configuration: the world's, whose tools get the last word; it must outlive the solver.
  explicit SoftBodySolver(CollisionConfiguration& configuration);
  ~SoftBodySolver() override;
  SoftBodySolver(const SoftBodySolver&) = delete;
  SoftBodySolver& operator=(const SoftBodySolver&) = delete;

  // See: btDefaultSoftBodySolver::solveConstraints
  void solveConstraints(btScalar timeStep) override;
  // See: btDefaultSoftBodySolver::predictMotion
  void predictMotion(btScalar timeStep) override;

 private:
  std::unique_ptr<detail::SoftBodySolverImpl> m_impl;
};

}  // namespace thintool
