// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/DeformableBodySolver.h>

#include "PairState.h"
#include "SoftBodySolverImpl.h"
#include "ToolState.h"

#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletSoftBody/btSoftBodyInternals.h>

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

// A node contact's impulse matrix against a multibody link, as Bullet builds its own
// (btSoftBodyInternals.h, CollideSDF_RD::DoNode): the link's response to a unit impulse along the
// contact's normal and two tangents, through the multibody's Jacobian at the node, added to the
// node's own inverse mass, inverted in the contact's frame. The tangents and Jacobians are left in
// the contact, for the solve to apply its impulses to the multibody with.
btMatrix3x3 impulseMatrixOnLink(btSoftBody::DeformableNodeRigidContact& contact,
                                const btMultiBodyLinkCollider& link) {
  const btVector3& normal = contact.m_cti.m_normal;
  contact.t1 = generateUnitOrthogonalVector(normal);
  contact.t2 = btCross(normal, contact.t1);
  findJacobian(&link, contact.jacobianData_normal, contact.m_node->m_x, normal);
  findJacobian(&link, contact.jacobianData_t1, contact.m_node->m_x, contact.t1);
  findJacobian(&link, contact.jacobianData_t2, contact.m_node->m_x, contact.t2);
  const btMatrix3x3 toContact(normal.getX(), normal.getY(), normal.getZ(), contact.t1.getX(), contact.t1.getY(),
                              contact.t1.getZ(), contact.t2.getX(), contact.t2.getY(), contact.t2.getZ());
  const btMatrix3x3 linkResponse =
      OuterProduct(&contact.jacobianData_normal.m_jacobians[0], &contact.jacobianData_t1.m_jacobians[0],
                   &contact.jacobianData_t2.m_jacobians[0],
                   &contact.jacobianData_normal.m_deltaVelocitiesUnitImpulse[0],
                   &contact.jacobianData_t1.m_deltaVelocitiesUnitImpulse[0],
                   &contact.jacobianData_t2.m_deltaVelocitiesUnitImpulse[0], link.m_multiBody->getNumDofs() + 6);
  return toContact.transpose() * (contact.m_node->m_effectiveMass_inv + linkResponse).inverse() * toContact;
}

}  // namespace

namespace detail {

// The tool's node contacts with the body in Bullet's solve: those ThinTool's detection found in
// this step's collision pass (BulletSettings::deformableNodeContacts) in place of Bullet's own. Each
// is built as Bullet builds its own (btSoftBodyInternals.h, CollideSDF_RD): on the plane the node
// must stay in front of, the offset its distance there at the start of the step (the node may close
// that far in the step), Bullet's coefficients, the impulse matrix of the node's effective mass and
// the tool's (a rigid body's, or a multibody link's through the multibody's Jacobian), resolved at
// the node's place now. Only nodes outside the tool's surface at the start get one.
void SoftBodySolverImpl::feedNodeContacts(btSoftBody& body) {
  for (Tool* tool : m_configuration.tools()) feedToolNodeContacts(body, *tool);
}

void SoftBodySolverImpl::feedToolNodeContacts(btSoftBody& body, Tool& tool) {
  bool feeds = false;
  for (const auto& pair : tool.state().pairs) feeds = feeds || (pair->softBody == &body && pair->feedsDeformable);
  if (!feeds) return;
  const btCollisionObject& object = tool.body();
  for (int c = 0; c < body.m_nodeRigidContacts.size();) {
    if (body.m_nodeRigidContacts[c].m_cti.m_colObj != &object) {
      ++c;
      continue;
    }
    body.m_nodeRigidContacts.swap(c, body.m_nodeRigidContacts.size() - 1);
    body.m_nodeRigidContacts.pop_back();
  }
  const btRigidBody* rigid = btRigidBody::upcast(&object);
  const btMultiBodyLinkCollider* link = btMultiBodyLinkCollider::upcast(&object);
  const btScalar bodyInverseMass = rigid != nullptr ? rigid->getInvMass() : btScalar(0);
  static const btMatrix3x3 noInverseInertia(0, 0, 0, 0, 0, 0, 0, 0, 0);
  const btMatrix3x3& inverseInertia = rigid != nullptr ? rigid->getInvInertiaTensorWorld() : noInverseInertia;
  const btScalar hardness = object.isStaticOrKinematicObject() ? body.m_cfg.kKHR : body.m_cfg.kCHR;
  for (auto& pair : tool.state().pairs) {
    if (pair->softBody != &body || !pair->feedsDeformable) continue;
    pair->feedsDeformable = false;
    // ThinTool's friction, as its response in the classic worlds has it (on by default). With
    // Bullet's coefficient always, a plate spinning at 178 rad/s dragged a sheet's nodes to 2.3 km/s
    // (generated seed 377).
    const btScalar friction = btScalar(pair->holdStaticFriction);
    const btScalar skin = btScalar(std::max(pair->skinInEffect, Real(0)));
    for (const PatchContact& found : pair->detection.contacts) {
      if (found.kind != ContactKind::SoftNode || found.softNodes[0] >= static_cast<Index>(body.m_nodes.size())) {
        continue;
      }
      btSoftBody::Node& node = body.m_nodes[static_cast<int>(found.softNodes[0])];
      if (node.m_battach != 0 || !(node.m_im + bodyInverseMass > 0)) continue;
      btSoftBody::DeformableNodeRigidContact contact;
      contact.t1 = contact.t2 = btVector3(0, 0, 0);  // a multibody's tangents, unused for a rigid body
      contact.m_node = &node;
      contact.m_cti.m_colObj = &object;
      contact.m_cti.m_normal = toBt(found.normal);
      contact.m_cti.m_offset = btScalar(dot(found.normal, toVec3(node.m_x)) + found.offset);
      // A node already behind the tool's surface at the start of the step (behind the grown face's
      // plane by more than the skin) is one the tool's sweep passed over: Bullet's contact would
      // push it out within the step, as a velocity, and a blade turning 123° a step flung a sheet
      // so at 266 m/s (generated seed 280). The last word puts it back after the solve, a move that
      // carries no velocity of its own. A node within the skin keeps its contact, whose negative
      // offset the solve works off as it does its own: the nodes a finger holds sit on that plane,
      // and without it lost their contact, and its friction, every other step (the gripper's cube
      // slipped 140 mm out of the fingers at kDF 2).
      if (!(contact.m_cti.m_offset >= -skin)) continue;
      const btVector3 arm = node.m_x - object.getWorldTransform().getOrigin();
      contact.m_c0 = link != nullptr
                         ? impulseMatrixOnLink(contact, *link)
                         : ImpulseMatrix(1, node.m_effectiveMass_inv, bodyInverseMass, inverseInertia, arm);
      contact.m_c1 = arm;
      contact.m_c2 = node.m_im;
      contact.m_c3 = friction;
      contact.m_c4 = hardness;
      contact.m_c5 = node.m_effectiveMass_inv;
      if (!isFinite(contact)) continue;
      body.m_nodeRigidContacts.push_back(contact);
      ++tool.state().deformableNodeContacts;
    }
  }
}

}  // namespace detail

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
      m_impl->feedNodeContacts(body);
      m_droppedContacts += dropNonFinite(body.m_nodeRigidContacts) + dropNonFinite(body.m_faceRigidContacts);
    }
  }
  btDeformableBodySolver::setConstraints(infoGlobal);
}

}  // namespace thintool
