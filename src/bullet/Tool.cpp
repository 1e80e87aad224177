// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "PairState.h"
#include "SweptProxy.h"

#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>

#include <algorithm>
#include <limits>

namespace thintool {

namespace detail {
PairState::PairState() = default;
PairState::~PairState() = default;
}  // namespace detail

Tool::Tool(btCollisionObject& body, const ToolOptions& options, std::vector<ToolModel> pieces,
           std::vector<Pose> pieceTransforms)
    : m_body(body), m_options(options), m_pieces(std::move(pieces)), m_pieceTransforms(std::move(pieceTransforms)) {
  Index largest = 0;
  for (const ToolModel& piece : m_pieces) {
    largest = std::max(largest, piece.nodeCount());
  }
  m_report.contacts.reserve(largest);
}

Tool::~Tool() { delete m_proxy; }

void Tool::resetMotion() {
  m_jumpNext = true;
  m_separationJump = true;
}

void Tool::trackMotion() {
  const Pose now = toPose(m_body.getWorldTransform());
  const bool jumped = m_jumpNext;
  m_poseBefore = m_motionTracked && !jumped ? m_poseNow : now;
  m_poseNow = now;
  m_motionTracked = true;
  m_jumpNext = false;
  // A dynamic tool set down by hand moves on from there in the same step: Bullet integrates it
  // after the collision pass, and the last word sweeps that motion from the pose set down.
  if (m_separationJump && dynamicBody() != nullptr && isFinite(now)) {
    m_separatedPose = now;
    m_hasSeparatedPose = true;
    m_separationJump = false;
  }
}

btRigidBody* Tool::rigidBody() const { return btRigidBody::upcast(&m_body); }

btRigidBody* Tool::dynamicBody() const {
  btRigidBody* rigid = rigidBody();
  return rigid != nullptr && !rigid->isStaticOrKinematicObject() ? rigid : nullptr;
}

void Tool::bodyMotion(Pose& outPrevious, Pose& outCurrent) const {
  if (dynamicBody() != nullptr) {
    outPrevious = toPose(m_body.getWorldTransform());
    outCurrent = toPose(m_body.getInterpolationWorldTransform());
    return;
  }
  outCurrent = toPose(m_body.getWorldTransform());
  outPrevious = m_motionTracked ? m_poseBefore : outCurrent;
}

Index Tool::nodeCount() const {
  Index count = 0;
  for (const ToolModel& piece : m_pieces) {
    count += piece.nodeCount();
  }
  return count;
}

detail::PairState& Tool::pairState(btSoftBody& softBody, Index piece) {
  for (auto& state : m_pairs) {
    if (state->softBody == &softBody && state->piece == piece) {
      return *state;
    }
  }
  m_pairs.push_back(std::make_unique<detail::PairState>());
  detail::PairState& state = *m_pairs.back();
  state.softBody = &softBody;
  state.piece = piece;
  return state;
}

namespace {

void captureInto(RestShape& shape, const btSoftBody& softBody) {
  std::vector<Vec3> positions;
  std::vector<Real> inverseMasses;
  positions.reserve(static_cast<std::size_t>(softBody.m_nodes.size()));
  inverseMasses.reserve(static_cast<std::size_t>(softBody.m_nodes.size()));
  for (int i = 0; i < softBody.m_nodes.size(); ++i) {
    positions.push_back(toVec3(softBody.m_nodes[i].m_x));
    inverseMasses.push_back(Real(softBody.m_nodes[i].m_im));
  }
  shape.capture(positions, inverseMasses);
}

}  // namespace

RestShape& Tool::restShape(const btSoftBody& softBody) {
  for (auto& rest : m_restShapes) {
    if (rest->softBody == &softBody) {
      if (rest->shape.nodeCount() != static_cast<Index>(softBody.m_nodes.size())) {
        captureInto(rest->shape, softBody);
      }
      return rest->shape;
    }
  }
  m_restShapes.push_back(std::make_unique<SoftRest>());
  m_restShapes.back()->softBody = &softBody;
  captureInto(m_restShapes.back()->shape, softBody);
  return m_restShapes.back()->shape;
}

void Tool::captureRestShape(const btSoftBody& softBody) {
  // restShape() captures only a body it has not seen; capture this one again whatever it had.
  captureInto(restShape(softBody), softBody);
}

const ToolStepReport& Tool::report() {
  m_report.contacts.clear();
  m_report.excludedNodes.clear();
  m_report.diagnostics = ToolDiagnostics{};
  m_report.wrench = Wrench{};
  ToolForce& contactForce = m_report.contactForce;
  contactForce.force = Vec3{};
  contactForce.torque = Vec3{};
  contactForce.faces.clear();
  ToolDiagnostics& diagnostics = m_report.diagnostics;
  diagnostics.lastWord = m_lastWord;
  diagnostics.nonFiniteWrites = m_lastWord.nonFiniteWrites;
  // A pose that is not finite was skipped by the step (the pairs held the tissue at the last good
  // one): report about that one too, so that no NaN reaches the report.
  Pose bodyPose = toPose(m_body.getWorldTransform());
  if (isFinite(bodyPose)) {
    m_lastFiniteBodyPose = bodyPose;
  } else {
    bodyPose = m_lastFiniteBodyPose;
  }
  contactForce.torquePoint = bodyPose.apply(m_options.force.torquePoint);
  diagnostics.lastWord.holdNodesShared = m_holdNodesShared;
  m_report.holdWrench.force = m_holdWrench.force;
  m_report.holdWrench.torque = m_holdWrench.torque - cross(bodyPose.translation, m_holdWrench.force);

  for (const auto& statePointer : m_pairs) {
    const detail::PairState& state = *statePointer;
    if (!state.live) {
      continue;
    }
    ++diagnostics.pairs;
    diagnostics.detection.accumulate(state.detection.counters);
    diagnostics.nodesMoved += static_cast<Index>(state.response.corrections.size());
    diagnostics.rejectedCorrections += state.response.rejected;
    diagnostics.detectionMicroseconds += state.detectionMicroseconds;
    diagnostics.responseMicroseconds += state.responseMicroseconds;
    StockPairs& stock = diagnostics.stockPairs;
    stock.deformableWorld += state.stock == detail::StockReason::DeformableWorld ? 1 : 0;
    stock.clusterCollision += state.stock == detail::StockReason::ClusterCollision ? 1 : 0;
    stock.noRigidContact += state.stock == detail::StockReason::NoRigidContact ? 1 : 0;
    stock.noFaces += state.stock == detail::StockReason::NoFaces ? 1 : 0;
    diagnostics.invalidPosePairs += state.invalidPose ? 1 : 0;
    diagnostics.nonFiniteWrites += state.nonFiniteWrites;
    for (int check = 1; check <= 2; ++check) {
      for (Index node : state.detection.excludedNodes[check - 1]) {
        m_report.excludedNodes.push_back({state.softBody, state.piece, node, check});
      }
    }

    // The piece's wrench is about the piece's origin; move the torque to the body's origin.
    const Pose piecePose = bodyPose * m_pieceTransforms[state.piece];
    const Wrench& wrench = state.response.wrench;
    m_report.wrench.force += wrench.force;
    m_report.wrench.torque +=
        wrench.torque + cross(piecePose.translation - bodyPose.translation, wrench.force);

    for (const FaceForce& face : state.force.faces) {
      contactForce.faces.push_back({state.softBody, state.piece, face});
      contactForce.force += face.force;
      contactForce.torque += cross(face.point - contactForce.torquePoint, face.force);
    }

    // What the soft solver left inside the tool, measured at the positions the step ended with.
    const ToolModel& model = m_pieces[state.piece];
    const btSoftBody& softBody = *state.softBody;
    for (const Contact& contact : state.detection.contacts) {
      m_report.contacts.push_back({&softBody, state.piece, contact});
      if (contact.softFace >= static_cast<Index>(softBody.m_faces.size())) {
        continue;
      }
      const btSoftBody::Face& face = softBody.m_faces[static_cast<int>(contact.softFace)];
      Vec3 point;
      for (int k = 0; k < 3; ++k) {
        point += toVec3(face.m_n[k]->m_x) * contact.barycentric[k];
      }
      // Inside a convex piece, the depth is the distance to the nearest face plane.
      const Vec3 local = piecePose.applyInverse(point);
      const Real penetration = -outsideDistance(model.planes, local);
      if (penetration > diagnostics.maxRemainingPenetration) {
        diagnostics.maxRemainingPenetration = penetration;
      }
    }
  }
  return m_report;
}

}  // namespace thintool
