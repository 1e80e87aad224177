// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers

#include "ToolReaction.h"

#include "geometry/Ccd.h"
#include "tool/PieceMotion.h"

#include <thintool/bullet/Convert.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <LinearMath/btTransformUtil.h>

#include <algorithm>
#include <cmath>

namespace thintool::detail {

namespace {

// The arc of a turning tool is sampled every 5° of its turn.
constexpr Real kMostTurnPerSample = Real(5) * kPi / 180;

// The impulse (N s) a node of inverse mass inverseNodeMass exchanges with a body of inverse
// effective mass inverseEffectiveMass at the point, the two closing at closing (m/s), or at the
// move's own speed if closingAtMoveSpeed and that is faster, along a move of distance (m) in a step
// of 1/inverseStep: the inelastic exchange, but no more than the node's change of momentum. 0 when
// nothing is exchanged.
btScalar exchangedImpulse(btScalar distance, btScalar inverseNodeMass, btScalar inverseEffectiveMass,
                          btScalar closing, btScalar inverseStep, bool closingAtMoveSpeed) {
  if (closingAtMoveSpeed) closing = std::max(closing, distance * inverseStep);
  btScalar impulse = std::max(btScalar(0), closing) / (inverseNodeMass + inverseEffectiveMass);
  if (inverseNodeMass > 0) {
    impulse = std::min(impulse, distance * inverseStep / inverseNodeMass);
  }
  return impulse > 0 && std::isfinite(impulse) ? impulse : 0;
}

}  // namespace

btScalar applyNodeReaction(btRigidBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity,
                           AppliedImpulse* applied, bool closingAtMoveSpeed) {
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
  const btScalar impulse =
      exchangedImpulse(distance, inverseNodeMass, inverseEffectiveMass, closing, inverseStep, closingAtMoveSpeed);
  if (impulse == 0) {
    return 0;
  }
  tool.applyImpulse(direction * -impulse, arm);
  if (applied != nullptr) applied->add(direction * -impulse, nodePosition);
  return impulse;
}

btScalar stopShortOfPinnedNode(btRigidBody& tool, const ToolModel& piece, const Pose& pieceNow, const Vec3& node,
                               Real inverseStep, bool forcesPending, AppliedImpulse* applied) {
  const btScalar step = btScalar(1 / inverseStep);
  const btVector3 at = toBt(node);
  const btVector3 arm = at - tool.getCenterOfMassPosition();
  // Bullet's solver adds the tool's force and torque over the step after the collision pass.
  btVector3 pendingLinear(0, 0, 0);
  btVector3 pendingAngular(0, 0, 0);
  if (forcesPending) {
    pendingLinear = tool.getTotalForce() * (tool.getInvMass() * step);
    pendingAngular = (tool.getInvInertiaTensorWorld() * tool.getTotalTorque()) * step;
    // Bullet's solver also turns the body by its implicit gyroscopic term (on by default): left
    // out, a 1.72 kg plate resting on a pinned node sank into it 6 µm a step (generated seed 4127).
    if ((tool.getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY) != 0) {
      pendingAngular += tool.computeGyroscopicImpulseImplicit_Body(step);
    }
  }
  // The speculative contact: the point's closing speed along the nearest face's normal now, the
  // pending forces' share included, at most the gap over the step.
  Index plane = 0;
  const Real gap = outsideDistance(piece.planes, pieceNow.applyInverse(node), &plane);
  const btVector3 outward = toBt(pieceNow.applyToDirection(piece.planes[plane].normal));
  const btVector3 pending = pendingLinear + pendingAngular.cross(arm);
  btScalar impulse = applyNodeReaction(tool, at, outward, 0, btScalar(inverseStep),
                                       outward * btScalar(gap * inverseStep) - pending, applied);

  // A turning tool's point does not move along its velocity: a 0.5 m plate turning at 1 rad/s
  // strays 0.1 mm from it in a 50 Hz step. Where the tool will stand after the step, integrated as
  // Bullet integrates it, the node is seen from there; still inside, the point gives the depth back.
  // So does a node the tool's motion would reach on its way, back to the face it reached it by:
  // outside at the end, it may be on the far side (generated seed 4352: jaws turning 50° a step
  // passed over a sheet's pinned corner). The node stays where it is. The way there is read as the
  // last word and the ground truth read a step, between the two poses: the origin along the chord,
  // the turn about one axis, sampled every 5°. Integrating a part of the step alone is no guide to
  // the way: past 45° a step Bullet turns a body by less than its angular velocity says, and not in
  // proportion to the time, so that a jaw spinning at 130 rad/s was seen from poses off its arc
  // between the step's two poses, and passed over a pinned corner (generated seed 8609 with
  // friction).
  const btTransform& bodyNow = tool.getCenterOfMassTransform();
  const btVector3 linear = tool.getLinearVelocity() + pendingLinear;
  const btVector3 angular = tool.getAngularVelocity() + pendingAngular;
  btTransform bodyEnd;
  btTransformUtil::integrateTransform(bodyNow, linear, angular, step, bodyEnd);
  const Pose bodyStart = toPose(bodyNow);
  const Pose inBody{bodyStart.rotation.transposed() * pieceNow.rotation,
                    bodyStart.applyInverse(pieceNow.translation)};
  const PieceMotion way(bodyStart, toPose(bodyEnd), kMostTurnPerSample, inBody);
  // A node inside already, if only by rounding on the face it lies on, leaves by the face nearest
  // it now, which the speculative contact above reads: the face nearest where the tool would leave
  // it can be the far one, and the two pushes then undid each other until a dynamic plate passed
  // through a pinned corner that lay on its face (generated seed 16707 with friction).
  Index reachedBy = gap < 0 ? plane : kInvalidIndex;
  Vec3 previous = pieceNow.applyInverse(node);
  for (int k = 1; k <= way.samples() && reachedBy == kInvalidIndex; ++k) {
    const Vec3 current = way.at(Real(k) / Real(way.samples())).applyInverse(node);
    const ClipResult path = clipSegmentConvex(piece.planes, 0, previous, current);
    if (path.hit) reachedBy = path.enterPlane;
    previous = current;
  }
  const Vec3 endLocal = way.end().applyInverse(node);
  Real depth = -outsideDistance(piece.planes, endLocal, &plane);
  if (reachedBy != kInvalidIndex) {
    plane = reachedBy;
    depth = -piece.planes[plane].signedDistance(endLocal);
  }
  if (depth > 0) {
    const btVector3 endOutward =
        bodyEnd.getBasis() * (bodyNow.getBasis().transpose() * toBt(pieceNow.applyToDirection(piece.planes[plane].normal)));
    const btVector3 closing = tool.getVelocityInLocalPoint(arm) - endOutward * btScalar(depth * inverseStep);
    impulse += applyNodeReaction(tool, at, endOutward, 0, btScalar(inverseStep), closing, applied);
  }
  return impulse;
}

btScalar applyNodeReaction(DynamicBody& tool, const btVector3& nodePosition, const btVector3& displacement,
                           btScalar inverseNodeMass, btScalar inverseStep, const btVector3& nodeVelocity,
                           bool closingAtMoveSpeed) {
  if (btRigidBody* rigid = tool.rigid()) {
    return applyNodeReaction(*rigid, nodePosition, displacement, inverseNodeMass, inverseStep, nodeVelocity,
                             tool.applied(), closingAtMoveSpeed);
  }
  const btScalar distance = displacement.length();
  if (!(distance > 0) || !std::isfinite(distance) || !(inverseNodeMass >= 0)) {
    return 0;
  }
  const btVector3 direction = displacement / distance;
  const DynamicBody::Row row = tool.row(nodePosition, direction);
  if (!(row.inverseMass > 0)) {
    return 0;  // the link cannot move along the move: nothing to exchange
  }
  const btScalar closing = row.speed - nodeVelocity.dot(direction);
  const btScalar impulse =
      exchangedImpulse(distance, inverseNodeMass, row.inverseMass, closing, inverseStep, closingAtMoveSpeed);
  if (impulse == 0) {
    return 0;
  }
  tool.applyAlongRow(-impulse);
  return impulse;
}

btScalar stopShortOfPinnedNode(DynamicBody& tool, const ToolModel& piece, const Pose& pieceNow, const Vec3& node,
                               Real inverseStep, bool forcesPending) {
  if (btRigidBody* rigid = tool.rigid()) {
    return stopShortOfPinnedNode(*rigid, piece, pieceNow, node, inverseStep, forcesPending, tool.applied());
  }
  Index plane = 0;
  const Real gap = outsideDistance(piece.planes, pieceNow.applyInverse(node), &plane);
  const btVector3 outward = toBt(pieceNow.applyToDirection(piece.planes[plane].normal));
  return applyNodeReaction(tool, toBt(node), outward, 0, btScalar(inverseStep), outward * btScalar(gap * inverseStep));
}

}  // namespace thintool::detail
