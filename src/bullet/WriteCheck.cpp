// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "WriteCheck.h"

#include "DynamicBody.h"

#include <thintool/core/Assert.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>

namespace thintool::detail {

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace

void checkWrite(const btVector3& before, const btVector3& after, Index& count) {
  const bool madeNonFinite = finite(before) && !finite(after);
  THINTOOL_ASSERT(!madeNonFinite);
  count += madeNonFinite ? 1 : 0;
}

BodyVelocities::BodyVelocities(const btRigidBody* body) : m_body(body) {
  if (body == nullptr) return;
  m_linear = body->getLinearVelocity();
  m_angular = body->getAngularVelocity();
}

BodyVelocities::BodyVelocities(const DynamicBody& body) : BodyVelocities(body.rigid()) {
  if (body.rigid() != nullptr || !body) return;
  m_link = &body;
  m_linkFinite = body.linkVelocitiesFinite();
}

void BodyVelocities::check(Index& count) const {
  if (m_link != nullptr) {
    const bool madeNonFinite = m_linkFinite && !m_link->linkVelocitiesFinite();
    THINTOOL_ASSERT(!madeNonFinite);
    count += madeNonFinite ? 1 : 0;
  }
  if (m_body == nullptr) return;
  checkWrite(m_linear, m_body->getLinearVelocity(), count);
  checkWrite(m_angular, m_body->getAngularVelocity(), count);
}

}  // namespace thintool::detail
