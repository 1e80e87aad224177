// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The last word in Bullet's deformable world: a solver to pass to btDeformableMultiBodyDynamicsWorld
/// (and to its btDeformableMultiBodyConstraintSolver) where btDeformableBodySolver was.
///
///     thintool::CollisionConfiguration configuration;
///     thintool::DeformableBodySolver deformableSolver(configuration);
///     btDeformableMultiBodyConstraintSolver constraintSolver;
///     constraintSolver.setDeformableSolver(&deformableSolver);
///     btDeformableMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &constraintSolver,
///                                              &configuration, &deformableSolver);
///
/// Bullet's deformable world solves its bodies implicitly with its own rigid contacts, which it
/// finds at one instant against a distance field of the tool: a thin or fast tool passes between
/// them. This solver is Bullet's own in every stage; after its last one, applyTransforms, which
/// moves each node to where the solve sends it, the tools of the configuration whose
/// ToolOptions::separation is enabled put every soft node and face near them back on their side,
/// as SoftBodySolver does in the classic worlds (response/Separation.h), with the node's velocity
/// along its move the faster of its own and the tool's; a dynamic tool takes the momentum that
/// velocity change gives the node (the move itself carries none after Bullet's solve). Then, for
/// tools with the energy guard on (EnergyGuardSettings), no node of a body the last word reached moves faster than speedFactor
/// times the faster of the tools' fastest corner and restingSpeed, or than the body's fastest node
/// at the start of the step: the guard's speed bound, without its energy bound or its bound on the
/// next step's forces. A swept tool's node contacts inside the solve are ThinTool's
/// (BulletSettings::deformableNodeContacts, on by default; on a multibody link through the
/// multibody's Jacobian), its face contacts Bullet's; with that option off, or for a discrete tool,
/// the pair's contacts are all Bullet's (ToolDiagnostics::stockPairs counts those pairs as
/// deformableWorld). There are no holds in the solve. What those contacts
/// applied to a tool's body over the step (each keeps the velocity change its impulses gave the soft
/// side, m_c5 times each impulse, in m_total_normal_dv and m_total_tangent_dv) is the tool's load,
/// with the last word's velocity changes: ToolStepReport::holdWrench.
///
/// With a tool registered, the solver also drops each of Bullet's rigid contacts that its detection
/// gave a value that is not finite, before the solve reads them (droppedContacts counts them): in
/// the float build Bullet's face contact on a sliver face (a crushed fold) gets NaN barycentric
/// weights, and the implicit solve spreads the NaN to every node of the body in one step.
///
/// Not in thintool/thintool.h: Bullet's deformable headers declare helpers at global scope (a
/// Clamp among them) that a program of the classic worlds need not see.

#include <thintool/core/Api.h>

#include <BulletSoftBody/btDeformableBodySolver.h>

#include <memory>

namespace thintool {

class CollisionConfiguration;
namespace detail {
class SoftBodySolverImpl;
}  // namespace detail

class THINTOOL_API DeformableBodySolver : public btDeformableBodySolver {
 public:
  /// configuration: the world's, whose tools get the last word; it must outlive the solver.
  explicit DeformableBodySolver(CollisionConfiguration& configuration);
  ~DeformableBodySolver() override;
  DeformableBodySolver(const DeformableBodySolver&) = delete;
  DeformableBodySolver& operator=(const DeformableBodySolver&) = delete;

  // See: btDeformableBodySolver::predictMotion
  void predictMotion(btScalar solverdt) override;
  // See: btDeformableBodySolver::applyTransforms
  void applyTransforms(btScalar timeStep) override;
  // See: btDeformableBodySolver::setConstraints
  void setConstraints(const btContactSolverInfo& infoGlobal) override;

  /// Bullet's rigid contacts (node and face) dropped for a value that is not finite, over the
  /// solver's life.
  long long droppedContacts() const { return m_droppedContacts; }

 private:
  CollisionConfiguration& m_configuration;
  long long m_droppedContacts = 0;
  std::unique_ptr<detail::SoftBodySolverImpl> m_impl;
};

}  // namespace thintool
