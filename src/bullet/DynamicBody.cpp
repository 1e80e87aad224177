// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "DynamicBody.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <LinearMath/btTransformUtil.h>

#include <cmath>

namespace thintool::detail {

DynamicBody DynamicBody::of(btCollisionObject& body, JacobianScratch& scratch, AppliedImpulse& applied) {
  if (btRigidBody* rigid = btRigidBody::upcast(&body)) {
    return rigid->isStaticOrKinematicObject() ? DynamicBody() : DynamicBody(*rigid, &applied);
  }
  btMultiBodyLinkCollider* link = btMultiBodyLinkCollider::upcast(&body);
  if (link == nullptr || link->m_multiBody == nullptr || link->isStaticOrKinematicObject()) {
    return DynamicBody();
  }
  if (link->m_link < 0 && link->m_multiBody->isBaseStaticOrKinematic()) {
    return DynamicBody();
  }
  DynamicBody view;
  view.m_link = link;
  view.m_scratch = &scratch;
  view.m_applied = &applied;
  return view;
}

DynamicBody::Row DynamicBody::row(const btVector3& point, const btVector3& direction) {
  m_rowPoint = point;
  m_rowDirection = direction;
  Row result;
  if (m_link == nullptr) return result;
  const btMultiBody& multiBody = *m_link->m_multiBody;
  const int size = 6 + multiBody.getNumDofs();
  JacobianScratch& s = *m_scratch;
  s.jacobian.resize(size);
  s.velocityChange.resize(size);
  multiBody.fillContactJacobianMultiDof(m_link->m_link, point, direction, &s.jacobian[0], s.reals, s.vectors,
                                        s.matrices);
  multiBody.calcAccelerationDeltasMultiDof(&s.jacobian[0], &s.velocityChange[0], s.reals, s.vectors);
  const btScalar* velocities = multiBody.getVelocityVector();
  for (int i = 0; i < size; ++i) {
    result.speed += s.jacobian[i] * velocities[i];
    result.inverseMass += s.jacobian[i] * s.velocityChange[i];
  }
  // M is positive definite: anything else is a multibody Bullet has not factored yet, or a broken
  // one, and the link is then taken as immovable.
  if (!std::isfinite(result.inverseMass) || !(result.inverseMass > 0) || !std::isfinite(result.speed)) {
    result.inverseMass = 0;
    if (!std::isfinite(result.speed)) result.speed = 0;
  }
  return result;
}

void DynamicBody::applyAlongRow(btScalar impulse) {
  if (!std::isfinite(impulse) || impulse == 0) return;
  if (m_link == nullptr) return;
  if (m_applied != nullptr) m_applied->add(m_rowDirection * impulse, m_rowPoint);
  m_link->m_multiBody->applyDeltaVeeMultiDof(&m_scratch->velocityChange[0], impulse);
}

void DynamicBody::applyImpulse(const btVector3& impulse, const btVector3& point) {
  if (m_rigid != nullptr) {
    if (m_applied != nullptr) m_applied->add(impulse, point);
    m_rigid->applyImpulse(impulse, point - m_rigid->getCenterOfMassPosition());
    return;
  }
  const btScalar magnitude = impulse.length();
  if (!(magnitude > 0) || !std::isfinite(magnitude)) return;
  if (row(point, impulse / magnitude).inverseMass > 0) applyAlongRow(magnitude);
}

bool DynamicBody::predictLinkPose(btScalar timeStep, btTransform& outPose) {
  if (m_link == nullptr) return false;
  const btMultiBody& multiBody = *m_link->m_multiBody;
  const btTransform& now = m_link->getWorldTransform();
  const int size = 6 + multiBody.getNumDofs();
  JacobianScratch& s = *m_scratch;
  s.jacobian.resize(size);
  const btScalar* velocities = multiBody.getVelocityVector();
  // Each component of the link frame's velocity is a Jacobian row times the joint velocities.
  const auto along = [&](const btVector3& angular, const btVector3& linear) {
    multiBody.fillConstraintJacobianMultiDof(m_link->m_link, now.getOrigin(), angular, linear, &s.jacobian[0], s.reals,
                                             s.vectors, s.matrices);
    btScalar speed = 0;
    for (int i = 0; i < size; ++i) speed += s.jacobian[i] * velocities[i];
    return speed;
  };
  const btVector3 zero(0, 0, 0);
  const btVector3 axes[3] = {btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)};
  btVector3 linear;
  btVector3 angular;
  for (int a = 0; a < 3; ++a) {
    linear[a] = along(zero, axes[a]);
    angular[a] = along(axes[a], zero);
  }
  if (!std::isfinite(linear.length2()) || !std::isfinite(angular.length2())) return false;
  btTransformUtil::integrateTransform(now, linear, angular, timeStep, outPose);
  return true;
}

void DynamicBody::activate() {
  if (m_rigid != nullptr) {
    m_rigid->activate();
  } else if (m_link != nullptr) {
    m_link->activate();
    m_link->m_multiBody->wakeUp();
  }
}

bool DynamicBody::linkVelocitiesFinite() const {
  if (m_link == nullptr) return true;
  const btMultiBody& multiBody = *m_link->m_multiBody;
  const btScalar* velocities = multiBody.getVelocityVector();
  for (int i = 0; i < 6 + multiBody.getNumDofs(); ++i) {
    if (!std::isfinite(velocities[i])) return false;
  }
  return true;
}

}  // namespace thintool::detail
