// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers

#include "ToolReaction.h"

#include <thintool/bullet/Convert.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <LinearMath/btTransformUtil.h>

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

btScalar stopShortOfPinnedNode(btRigidBody& tool, const ToolModel& piece, const Pose& pieceNow, const Vec3& node,
                               Real inverseStep, bool forcesPending) {
  const btScalar step = btScalar(1 / inverseStep);
  const btVector3 at = toBt(node);
  const btVector3 arm = at - tool.getCenterOfMassPosition();
  // Bullet's solver adds the tool's force and torque over the step after the collision pass.
  btVector3 pendingLinear(0, 0, 0);
  btVector3 pendingAngular(0, 0, 0);
  if (forcesPending) {
    pendingLinear = tool.getTotalForce() * (tool.getInvMass() * step);
    pendingAngular = (tool.getInvInertiaTensorWorld() * tool.getTotalTorque()) * step;
  }
  // The speculative contact: the point's closing speed along the nearest face's normal now, the
  // pending forces' share included, at most the gap over the step.
  Index plane = 0;
  const Real gap = outsideDistance(piece.planes, pieceNow.applyInverse(node), &plane);
  const btVector3 outward = toBt(pieceNow.applyToDirection(piece.planes[plane].normal));
  const btVector3 pending = pendingLinear + pendingAngular.cross(arm);
  btScalar impulse =
      applyNodeReaction(tool, at, outward, 0, btScalar(inverseStep), outward * btScalar(gap * inverseStep) - pending);

  // A turning tool's point does not move along its velocity: a 0.5 m plate turning at 1 rad/s
  // strays 0.1 mm from it in a 50 Hz step. Where the tool will stand after the step, integrated as
  // Bullet integrates it, the node is seen from there; still inside, the point gives the depth back.
  const btTransform& bodyNow = tool.getCenterOfMassTransform();
  btTransform bodyEnd;
  btTransformUtil::integrateTransform(bodyNow, tool.getLinearVelocity() + pendingLinear,
                                      tool.getAngularVelocity() + pendingAngular, step, bodyEnd);
  const Vec3 seenFromEnd = toVec3(bodyNow * bodyEnd.invXform(at));
  const Real depth = -outsideDistance(piece.planes, pieceNow.applyInverse(seenFromEnd), &plane);
  if (depth > 0) {
    const btVector3 endOutward =
        bodyEnd.getBasis() * (bodyNow.getBasis().transpose() * toBt(pieceNow.applyToDirection(piece.planes[plane].normal)));
    const btVector3 closing = tool.getVelocityInLocalPoint(arm) - endOutward * btScalar(depth * inverseStep);
    impulse += applyNodeReaction(tool, at, endOutward, 0, btScalar(inverseStep), closing);
  }
  return impulse;
}

}  // namespace thintool::detail
