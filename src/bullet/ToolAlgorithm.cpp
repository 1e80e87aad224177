// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ToolAlgorithm.h"

#include "PairState.h"
#include "SoftSurface.h"

#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyInternals.h>
#include <BulletSoftBody/btSoftBodySolvers.h>

#include <chrono>

namespace thintool::detail {

namespace {

using Clock = std::chrono::steady_clock;

double microsecondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

Aabb worldBounds(const Aabb& local, const Pose& pose) {
  Aabb box;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                 (corner & 4) ? local.max.z : local.min.z};
    box.include(pose.apply(p));
  }
  return box;
}

// The solver contact that keeps a moved node out of the tool during Bullet's position
// iterations, built as Bullet's CollideSDF_RS builds its own, with the entry-side plane.
btSoftBody::RContact solverContact(btSoftBody::Node& node, const NodeCorrection& correction,
                                   const btCollisionObject& toolObject, const btRigidBody* dynamicBody,
                                   btScalar timeStep, btScalar hardness) {
  btSoftBody::RContact contact;
  contact.m_cti.m_colObj = &toolObject;
  contact.m_cti.m_normal = toBt(correction.planeNormal);
  contact.m_cti.m_offset = btScalar(correction.planeOffset);
  contact.m_node = &node;
  const btScalar inverseMassTool = dynamicBody != nullptr ? dynamicBody->getInvMass() : btScalar(0);
  static const btMatrix3x3 zero(0, 0, 0, 0, 0, 0, 0, 0, 0);
  const btMatrix3x3& inverseInertia = dynamicBody != nullptr ? dynamicBody->getInvInertiaTensorWorld() : zero;
  const btVector3 arm = node.m_x - toolObject.getWorldTransform().getOrigin();
  contact.m_c0 = ImpulseMatrix(timeStep, node.m_im, inverseMassTool, inverseInertia, arm);
  contact.m_c1 = arm;
  contact.m_c2 = node.m_im * timeStep;
  contact.m_c3 = 1;  // frictionless: the tangential motion is left alone
  contact.m_c4 = hardness;
  return contact;
}

}  // namespace

ToolAlgorithm::ToolAlgorithm(const btCollisionAlgorithmConstructionInfo& info, Tool& tool, PairState& state,
                             bool swapped)
    : btCollisionAlgorithm(info), m_tool(tool), m_state(state), m_swapped(swapped) {}

ToolAlgorithm::~ToolAlgorithm() { m_state.separate(); }

void ToolAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                     const btDispatcherInfo& /*dispatchInfo*/, btManifoldResult* /*resultOut*/) {
  const btCollisionObjectWrapper* softWrap = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* toolWrap = m_swapped ? body0 : body1;
  btSoftBody& softBody = *const_cast<btSoftBody*>(btSoftBody::upcast(softWrap->getCollisionObject()));
  const btCollisionObject& toolObject = *toolWrap->getCollisionObject();
  PairState& state = m_state;
  state.clearResults();
  state.live = true;

  // As the stock algorithm: pairs the soft body was told to ignore are ignored.
  if (softBody.m_collisionDisabledObjects.findLinearSearch(&toolObject) != softBody.m_collisionDisabledObjects.size()) {
    return;
  }
  // The deformable world solves other contact types; hand its pairs to Bullet unchanged.
  if (softBody.getSoftBodySolver() == nullptr ||
      softBody.getSoftBodySolver()->getSolverType() != btSoftBodySolver::DEFAULT_SOLVER) {
    state.unsupported = true;
    if (softBody.getSoftBodySolver() != nullptr) {
      softBody.getSoftBodySolver()->processCollision(&softBody, toolWrap);
    }
    return;
  }

  const Pose pose = toPose(toolWrap->getWorldTransform());
  if (!isFinite(pose)) {
    state.invalidPose = true;
    return;
  }
  const auto start = Clock::now();
  const ToolOptions& options = m_tool.m_options;
  const ToolModel& model = m_tool.m_pieces[state.piece];

  ensureFaceTree(softBody);
  if (state.facesSeen != softBody.m_faces.size()) {
    state.facesSeen = softBody.m_faces.size();
    state.patch.orientation = surfaceOrientation(softBody);
    state.patch.positions.reserve(softBody.m_nodes.size());
    state.patch.inverseMasses.reserve(softBody.m_nodes.size());
    state.patch.nodeIds.reserve(softBody.m_nodes.size());
    state.patch.faces.reserve(softBody.m_faces.size());
    state.patch.faceIds.reserve(softBody.m_faces.size());
    state.contacts.reserve(model.nodeCount());
    state.corrections.reserve(softBody.m_nodes.size());
    state.traversalStack.reserve(256);
  }

  DetectionParameters parameters;
  parameters.skin = options.skin >= 0 ? options.skin : Real(softBody.getCollisionShape()->getMargin());
  parameters.filters = options.filters;
  if (parameters.filters.reverseRayLength <= 0) {
    parameters.filters.reverseRayLength = length(toVec3(softBody.m_bounds[1] - softBody.m_bounds[0]));
  }

  gatherPatch(softBody, worldBounds(model.bounds, pose).expanded(parameters.skin), state);
  const SoftBodyRayQuery reverseQuery(softBody, state.traversalStack);
  detectContacts(model, pose, state.patch, &reverseQuery, parameters, state.history, m_tool.m_detectionWorkspace,
                 state.contacts, state.counters);
  const auto detected = Clock::now();

  const btScalar timeStep = softBody.m_sst.sdt;
  computeResponse(model, pose, state.patch, state.contacts, parameters.skin, timeStep, options.response,
                  m_tool.m_responseWorkspace, state.corrections, state.wrench);

  const btRigidBody* rigidBody = btRigidBody::upcast(&toolObject);
  btRigidBody* dynamicBody =
      rigidBody != nullptr && !rigidBody->isStaticOrKinematicObject() ? const_cast<btRigidBody*>(rigidBody) : nullptr;
  const bool addSolverContacts =
      options.response.kind == ResponseKind::Constraint && options.response.solverContacts;
  // No node can sensibly be carried farther than the soft body is wide within one step.
  const btScalar largestCarry = (softBody.m_bounds[1] - softBody.m_bounds[0]).length();
  for (const NodeCorrection& correction : state.corrections) {
    if (!isFinite(correction.displacement) || !isFinite(correction.planeNormal)) {
      ++state.rejectedCorrections;
      continue;
    }
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(state.patch.nodeIds[correction.vertex])];
    const btVector3 displacement = toBt(correction.displacement);
    node.m_x += displacement;
    if (addSolverContacts) {
      // Bullet's solver also cancels the node's approach relative to the tool's velocity. After a
      // jump of the tool (a device re-homed, a pose set by hand) that velocity is meaningless and
      // would fling the node across the scene; such a contact is left to the projection alone.
      const btVector3 toolMotion =
          rigidBody != nullptr ? rigidBody->getVelocityInLocalPoint(node.m_x - rigidBody->getCenterOfMassPosition()) *
                                     timeStep
                               : btVector3(0, 0, 0);
      const btScalar approach = (node.m_x - node.m_q - toolMotion).dot(toBt(correction.planeNormal));
      if (approach < -largestCarry) {
        ++state.solverContactsSkipped;
      } else {
        softBody.m_rcontacts.push_back(solverContact(node, correction, toolObject, dynamicBody, timeStep,
                                                     btScalar(options.response.solverHardness)));
      }
    }
    if (dynamicBody != nullptr) {
      // The node's change of momentum, taken from the tool.
      dynamicBody->applyImpulse(displacement * (-1 / (node.m_im * timeStep)),
                                node.m_x - dynamicBody->getCenterOfMassPosition());
    }
  }
  if (dynamicBody != nullptr && !state.corrections.empty()) {
    dynamicBody->activate();
  }
  releasePatch(state);
  const auto responded = Clock::now();
  state.detectionMicroseconds = microsecondsBetween(start, detected);
  state.responseMicroseconds = microsecondsBetween(detected, responded);
}

}  // namespace thintool::detail
