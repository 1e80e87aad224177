// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers

#include "ToolReaction.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>

namespace thintool::detail {

btScalar applyNodeReaction(btRigidBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity) {
  const btScalar distance = displacement.length();
  if (!(distance > 0) || !std::isfinite(distance) || !(inverseNodeMass >= 0)) {
    return 0;
  }
  const btVector3 direction = displacement / distance;
  const btVector3 arm = nodePosition - tool.getCenterOfMassPosition();
  const btVector3 armCrossDirection = arm.cross(direction);
  const btScalar inverseEffectiveMass =
      tool.getInvMass() + armCrossDirection.dot(tool.getInvInertiaTensorWorld() * armCrossDirection);
  const btScalar inverseReducedMass = inverseNodeMass + inverseEffectiveMass;
  if (!(inverseReducedMass > 0)) {
    return 0;  // neither gives way: nothing to exchange
  }
  const btScalar closing = (tool.getVelocityInLocalPoint(arm) - nodeVelocity).dot(direction);
  btScalar impulse = std::max(btScalar(0), closing) / inverseReducedMass;
  if (inverseNodeMass > 0) {
    impulse = std::min(impulse, distance * inverseStep / inverseNodeMass);
  }
  if (!(impulse > 0) || !std::isfinite(impulse)) {
    return 0;
  }
  tool.applyImpulse(direction * -impulse, arm);
  return impulse;
}

}  // namespace thintool::detail
