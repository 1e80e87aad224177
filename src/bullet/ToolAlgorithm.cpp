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

#include <algorithm>
#include <chrono>
#include <memory>

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

// The solver contact that holds a moved node, built as Bullet's CollideSDF_RS builds its own.
// PSolve_RContacts corrects x -= n·(dn + c4·dp) while dn <= 0, where dn is the node's motion this
// step relative to the contact body's, (x - q - v_body·dt)·n. A body whose velocity is the node's
// own projected motion makes dn = 0 where the projection left the node, and with c4 = 0 the
// contact restores that position along n whenever the links or the pressure pull the node back
// in, and never pulls it out further: a one-sided hold. The body has zero inverse mass, so the
// solver's impulses on it go nowhere; the tool's reaction comes from the projection.
btSoftBody::RContact holdContact(btSoftBody::Node& node, const Vec3& normal, btRigidBody& holdBody,
                                 btScalar timeStep) {
  holdBody.setLinearVelocity((node.m_x - node.m_q) / timeStep);
  holdBody.setAngularVelocity(btVector3(0, 0, 0));
  btSoftBody::RContact contact;
  contact.m_cti.m_colObj = &holdBody;
  contact.m_cti.m_normal = toBt(normal);
  contact.m_cti.m_offset = -contact.m_cti.m_normal.dot(node.m_x);
  contact.m_node = &node;
  static const btMatrix3x3 zero(0, 0, 0, 0, 0, 0, 0, 0, 0);
  contact.m_c0 = ImpulseMatrix(timeStep, node.m_im, 0, zero, btVector3(0, 0, 0));
  contact.m_c1 = btVector3(0, 0, 0);
  contact.m_c2 = node.m_im * timeStep;
  contact.m_c3 = 1;  // frictionless: the tangential motion is left alone
  contact.m_c4 = 0;  // no positional term: the projection already placed the node
  return contact;
}

// Writes the corrections into the soft body: the moves, the solver's holds, and for a dynamic tool
// the reaction. A correction that is not finite is counted and never written.
void applyResponse(PairState& state, btSoftBody& softBody, const btCollisionObject& toolObject,
                   const ResponseSettings& settings, btScalar timeStep) {
  const btRigidBody* rigidBody = btRigidBody::upcast(&toolObject);
  btRigidBody* dynamicBody =
      rigidBody != nullptr && !rigidBody->isStaticOrKinematicObject() ? const_cast<btRigidBody*>(rigidBody) : nullptr;
  const bool holdInSolver = settings.kind == ResponseKind::Constraint && settings.holdInSolver;
  Index holdsUsed = 0;
  for (const NodeCorrection& correction : state.corrections) {
    if (!isFinite(correction.displacement) || !isFinite(correction.normal)) {
      ++state.rejectedCorrections;
      continue;
    }
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(state.patch.nodeIds[correction.vertex])];
    const btVector3 displacement = toBt(correction.displacement);
    node.m_x += displacement;
    if (holdInSolver) {
      if (holdsUsed == state.holdBodies.size()) {
        state.holdBodies.push_back(
            std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, nullptr)));
      }
      softBody.m_rcontacts.push_back(holdContact(node, correction.normal, *state.holdBodies[holdsUsed++], timeStep));
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
}

}  // namespace

ToolAlgorithm::ToolAlgorithm(const btCollisionAlgorithmConstructionInfo& info, Tool& tool, Mode mode,
                             PairState* state, btSoftBody* softBody, bool swapped)
    : btCollisionAlgorithm(info), m_tool(tool), m_mode(mode), m_state(state), m_softBody(softBody), m_swapped(swapped) {}

ToolAlgorithm::~ToolAlgorithm() {
  if (m_mode == Mode::OnePiece) {
    m_state->separate();
  } else if (m_mode == Mode::WholeTool) {
    for (Index piece = 0; piece < m_tool.pieceCount(); ++piece) {
      m_tool.pairState(*m_softBody, piece).separate();
    }
  }
}

void ToolAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                     const btDispatcherInfo& /*dispatchInfo*/, btManifoldResult* /*resultOut*/) {
  if (m_mode == Mode::Idle) {
    return;
  }
  const btCollisionObjectWrapper* softWrap = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* toolWrap = m_swapped ? body0 : body1;
  btSoftBody& softBody = *const_cast<btSoftBody*>(btSoftBody::upcast(softWrap->getCollisionObject()));
  const btCollisionObject& toolBody = m_tool.body();
  if (m_mode == Mode::OnePiece) {
    const Pose pose = toPose(toolWrap->getWorldTransform());
    processPiece(*m_state, softBody, toolBody, toolWrap, m_state->hasPreviousPose ? m_state->previousPose : pose, pose,
                 false);
    return;
  }
  Pose bodyBefore;
  Pose bodyNow;
  m_tool.bodyMotion(bodyBefore, bodyNow);
  for (Index piece = 0; piece < m_tool.pieceCount(); ++piece) {
    PairState& state = m_tool.pairState(softBody, piece);
    processPiece(state, softBody, toolBody, toolWrap, bodyBefore * m_tool.pieceTransform(piece),
                 bodyNow * m_tool.pieceTransform(piece), true);
  }
}

void ToolAlgorithm::processPiece(PairState& state, btSoftBody& softBody, const btCollisionObject& toolBody,
                                 const btCollisionObjectWrapper* toolWrap, const Pose& previousPose, const Pose& pose,
                                 bool swept) {
  state.clearResults();
  state.live = true;

  // As the stock algorithm: pairs the soft body was told to ignore are ignored.
  if (softBody.m_collisionDisabledObjects.findLinearSearch(&toolBody) != softBody.m_collisionDisabledObjects.size()) {
    return;
  }
  // The deformable world solves other contact types; hand its pairs to Bullet unchanged.
  if (softBody.getSoftBodySolver() == nullptr ||
      softBody.getSoftBodySolver()->getSolverType() != btSoftBodySolver::DEFAULT_SOLVER) {
    state.unsupported = true;
    if (softBody.getSoftBodySolver() != nullptr && !swept) {
      softBody.getSoftBodySolver()->processCollision(&softBody, toolWrap);
    }
    return;
  }
  if (!isFinite(pose) || !isFinite(previousPose)) {
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
    state.patch.previousPositions.reserve(softBody.m_nodes.size());
    state.patch.inverseMasses.reserve(softBody.m_nodes.size());
    state.patch.nodeIds.reserve(softBody.m_nodes.size());
    state.patch.faces.reserve(softBody.m_faces.size());
    state.patch.faceIds.reserve(softBody.m_faces.size());
    state.contacts.reserve(model.nodeCount());
    state.corrections.reserve(softBody.m_nodes.size());
    state.traversalStack.reserve(256);
    state.sides.resize(static_cast<Index>(softBody.m_nodes.size()), static_cast<Index>(softBody.m_faces.size()));
  }

  const Real skin = options.skin >= 0 ? options.skin : Real(softBody.getCollisionShape()->getMargin());
  Aabb reach = worldBounds(model.bounds, pose);
  if (swept) {
    // The whole motion, and soft faces that move as far as the soft body moved last step.
    reach.include(worldBounds(model.bounds, previousPose));
    reach = reach.expanded(2 * state.softReach);
  }
  gatherPatch(softBody, reach.expanded(skin), state);

  if (swept) {
    detectSwept(model, previousPose, pose, state.patch, skin, state.sides, m_tool.m_sweptWorkspace, state.contacts,
                state.counters);
    state.softReach = 0;
    for (Index v = 0; v < state.patch.vertexCount(); ++v) {
      state.softReach = std::max(state.softReach, length(state.patch.positions[v] - state.patch.previousPositions[v]));
    }
  } else {
    DetectionParameters parameters;
    parameters.skin = skin;
    parameters.filters = options.filters;
    if (parameters.filters.reverseRayLength <= 0) {
      parameters.filters.reverseRayLength = length(toVec3(softBody.m_bounds[1] - softBody.m_bounds[0]));
    }
    const SoftBodyRayQuery reverseQuery(softBody, state.traversalStack);
    detectContacts(model, pose, state.patch, &reverseQuery, parameters, state.history, m_tool.m_detectionWorkspace,
                   state.contacts, state.counters);
  }
  const auto detected = Clock::now();

  const btScalar timeStep = softBody.m_sst.sdt;
  ResponseSettings response = options.response;
  response.guardNodes = response.guardNodes && !swept;  // swept detection tests every node itself
  computeResponse(model, pose, previousPose, state.patch, state.contacts, skin, timeStep, response,
                  m_tool.m_responseWorkspace, state.corrections, state.wrench);
  state.previousPose = pose;
  state.hasPreviousPose = true;
  applyResponse(state, softBody, toolBody, options.response, timeStep);
  releasePatch(state);
  const auto responded = Clock::now();
  state.detectionMicroseconds = microsecondsBetween(start, detected);
  state.responseMicroseconds = microsecondsBetween(detected, responded);
}

}  // namespace thintool::detail
