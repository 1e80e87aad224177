// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/DeformableBodySolver.h>

#include "SoftBodySolverImpl.h"

#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace thintool {
namespace {

bool isFinite(const btMatrix3x3& m) {
  return thintool::isFinite(toVec3(m[0])) && thintool::isFinite(toVec3(m[1])) && thintool::isFinite(toVec3(m[2]));
}

// What the solve reads of a contact: its normal and offset, impulse matrices, anchor and masses,
// and for a face the point and weights it spreads the impulse with.
bool isFinite(const btSoftBody::DeformableRigidContact& contact) {
  return thintool::isFinite(toVec3(contact.m_cti.m_normal)) && std::isfinite(contact.m_cti.m_offset) &&
         isFinite(contact.m_c0) && isFinite(contact.m_c5) && thintool::isFinite(toVec3(contact.m_c1)) &&
         std::isfinite(contact.m_c2) && std::isfinite(contact.m_c3) && std::isfinite(contact.m_c4);
}

bool isFinite(const btSoftBody::DeformableFaceRigidContact& contact) {
  return isFinite(static_cast<const btSoftBody::DeformableRigidContact&>(contact)) &&
         thintool::isFinite(toVec3(contact.m_contactPoint)) && thintool::isFinite(toVec3(contact.m_bary)) &&
         thintool::isFinite(toVec3(contact.m_weights));
}

// Order is kept up to the first contact dropped, so that a step without one is Bullet's exactly.
template <class Contact>
long long dropNonFinite(btAlignedObjectArray<Contact>& contacts) {
  long long dropped = 0;
  for (int c = 0; c < contacts.size();) {
    if (isFinite(contacts[c])) {
      ++c;
      continue;
    }
    contacts.swap(c, contacts.size() - 1);
    contacts.pop_back();
    ++dropped;
  }
  return dropped;
}

// The impulse a rigid contact of Bullet's solve applied to its rigid body or multibody link over the
// step. The contact keeps the velocity change its impulses gave the soft side, m_c5 (the soft
// side's inverse mass there) times each impulse, summed with the sign reversed in
// m_total_normal_dv and m_total_tangent_dv (btDeformableRigidContactConstraint::solveConstraint),
// so the impulses sum to -m_c5⁻¹ times that change. A contact whose soft side cannot move (m_c5
// singular: pinned nodes) applied none.
btVector3 impulseOnRigid(const btDeformableRigidContactConstraint& constraint) {
  const btMatrix3x3& inverseMass = constraint.m_contact->m_c5;
  const btScalar determinant = inverseMass.determinant();
  if (!(std::abs(determinant) > std::numeric_limits<btScalar>::min())) return btVector3(0, 0, 0);
  return -(inverseMass.inverse() * (constraint.m_total_normal_dv + constraint.m_total_tangent_dv));
}

}  // namespace

DeformableBodySolver::DeformableBodySolver(CollisionConfiguration& configuration)
    : m_configuration(configuration),
      m_impl(std::make_unique<detail::SoftBodySolverImpl>(configuration, m_softBodies, true)) {}

DeformableBodySolver::~DeformableBodySolver() = default;

void DeformableBodySolver::predictMotion(btScalar solverdt) {
  m_impl->beginToolSteps(solverdt);
  m_impl->rememberSpeeds();
  btDeformableBodySolver::predictMotion(solverdt);
}

void DeformableBodySolver::applyTransforms(btScalar timeStep) {
  m_impl->rememberStarts();
  btDeformableBodySolver::applyTransforms(timeStep);
  m_impl->lastWordAfterTransforms();
  // What the tools carried in Bullet's solve, its contacts' impulses, adds to what the last word's
  // moves put on them (ToolStepReport::holdWrench).
  if (m_configuration.tools().empty() || m_objective == nullptr) return;
  const btDeformableContactProjection& projection = m_objective->m_projection;
  // One slot a soft body, resized only when the bodies' count changes: those past it are stale.
  const auto addImpulses = [&](const auto& perBody, const auto& pointOf) {
    for (int s = 0; s < std::min(m_softBodies.size(), perBody.size()); ++s) {
      for (int c = 0; c < perBody[s].size(); ++c) {
        const auto& constraint = perBody[s][c];
        m_impl->addSolverImpulse(*constraint.m_contact->m_cti.m_colObj, impulseOnRigid(constraint),
                                 pointOf(constraint), timeStep);
      }
    }
  };
  addImpulses(projection.m_nodeRigidConstraints,
              [](const btDeformableNodeRigidContactConstraint& node) { return node.m_node->m_x; });
  addImpulses(projection.m_faceRigidConstraints,
              [](const btDeformableFaceRigidContactConstraint& face) { return face.getContact()->m_contactPoint; });
}

void DeformableBodySolver::setConstraints(const btContactSolverInfo& infoGlobal) {
  if (!m_configuration.tools().empty()) {
    for (int s = 0; s < m_softBodies.size(); ++s) {
      btSoftBody& body = *m_softBodies[s];
      m_droppedContacts += dropNonFinite(body.m_nodeRigidContacts) + dropNonFinite(body.m_faceRigidContacts);
    }
  }
  btDeformableBodySolver::setConstraints(infoGlobal);
}

}  // namespace thintool
