// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "PairState.h"
#include "SweptProxy.h"
#include "ToolState.h"

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

ToolState::ToolState(btCollisionObject& toolBody, const ToolOptions& toolOptions, std::vector<ToolModel> toolPieces,
                     std::vector<Pose> toolPieceTransforms)
    : body(toolBody),
      options(toolOptions),
      pieces(std::move(toolPieces)),
      pieceTransforms(std::move(toolPieceTransforms)) {
  Index largest = 0;
  for (const ToolModel& piece : pieces) {
    largest = std::max(largest, piece.nodeCount());
  }
  report.contacts.reserve(largest);
}

ToolState::~ToolState() { delete proxy; }

void ToolState::trackMotion() {
  const Pose now = toPose(body.getWorldTransform());
  const bool jumped = jumpNext;
  poseBefore = motionTracked && !jumped ? poseNow : now;
  poseNow = now;
  motionTracked = true;
  jumpNext = false;
  // A dynamic tool set down by hand moves on from there in the same step: Bullet integrates it
  // after the collision pass, and the last word sweeps that motion from the pose set down.
  if (separationJump && dynamic() && isFinite(now)) {
    separatedPose = now;
    hasSeparatedPose = true;
    separationJump = false;
  }
}

btRigidBody* ToolState::dynamicBody() const {
  btRigidBody* rigid = btRigidBody::upcast(&body);
  return rigid != nullptr && !rigid->isStaticOrKinematicObject() ? rigid : nullptr;
}

DynamicBody ToolState::dynamic() const { return DynamicBody::of(body, jacobianScratch, applied); }

void ToolState::bodyMotion(Pose& outPrevious, Pose& outCurrent) const {
  if (DynamicBody view = dynamic()) {
    outPrevious = toPose(body.getWorldTransform());
    outCurrent = toPose(body.getInterpolationWorldTransform());
    // Bullet 3.24's soft multibody world leaves a link's interpolation transform at its pose now:
    // the link's present velocity over the step predicts it (the step is known once
    // thintool::SoftBodySolver has begun it; without that solver, no prediction).
    btTransform predicted;
    if (stepLength > 0 && view.predictLinkPose(stepLength, predicted)) {
      outCurrent = toPose(predicted);
    }
    return;
  }
  outCurrent = toPose(body.getWorldTransform());
  outPrevious = motionTracked ? poseBefore : outCurrent;
}

PairState& ToolState::pairState(btSoftBody& softBody, Index piece) {
  for (auto& state : pairs) {
    if (state->softBody == &softBody && state->piece == piece) {
      return *state;
    }
  }
  pairs.push_back(std::make_unique<PairState>());
  PairState& state = *pairs.back();
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

RestShape& ToolState::restShape(const btSoftBody& softBody) {
  for (auto& rest : restShapes) {
    if (rest->softBody == &softBody) {
      if (rest->shape.nodeCount() != static_cast<Index>(softBody.m_nodes.size())) {
        captureInto(rest->shape, softBody);
      }
      return rest->shape;
    }
  }
  restShapes.push_back(std::make_unique<SoftRest>());
  restShapes.back()->softBody = &softBody;
  captureInto(restShapes.back()->shape, softBody);
  return restShapes.back()->shape;
}

}  // namespace detail

Tool::Tool(btCollisionObject& body, const ToolOptions& options, std::vector<ToolModel> pieces,
           std::vector<Pose> pieceTransforms)
    : m_state(std::make_unique<detail::ToolState>(body, options, std::move(pieces), std::move(pieceTransforms))) {}

Tool::~Tool() = default;

const std::string& Tool::name() const { return m_state->options.name; }
btCollisionObject& Tool::body() const { return m_state->body; }
const ToolOptions& Tool::options() const { return m_state->options; }
Index Tool::pieceCount() const { return static_cast<Index>(m_state->pieces.size()); }
const ToolModel& Tool::piece(Index i) const { return m_state->pieces[i]; }
const Pose& Tool::pieceTransform(Index i) const { return m_state->pieceTransforms[i]; }

void Tool::resetMotion() {
  m_state->jumpNext = true;
  m_state->separationJump = true;
}

btRigidBody* Tool::rigidBody() const { return btRigidBody::upcast(&m_state->body); }

btRigidBody* Tool::dynamicBody() const { return m_state->dynamicBody(); }

Index Tool::nodeCount() const {
  Index count = 0;
  for (const ToolModel& piece : m_state->pieces) {
    count += piece.nodeCount();
  }
  return count;
}

void Tool::captureRestShape(const btSoftBody& softBody) {
  // restShape() captures only a body it has not seen; capture this one again whatever it had.
  detail::captureInto(m_state->restShape(softBody), softBody);
}

const ToolStepReport& Tool::report() {
  detail::ToolState& t = *m_state;
  t.report.contacts.clear();
  t.report.excludedNodes.clear();
  t.report.diagnostics = ToolDiagnostics{};
  t.report.wrench = Wrench{};
  ToolForce& contactForce = t.report.contactForce;
  contactForce.force = Vec3{};
  contactForce.torque = Vec3{};
  contactForce.faces.clear();
  ToolDiagnostics& diagnostics = t.report.diagnostics;
  diagnostics.lastWord = t.lastWord;
  diagnostics.nonFiniteWrites = t.lastWord.nonFiniteWrites;
  // A pose that is not finite was skipped by the step (the pairs held the tissue at the last good
  // one): report about that one too, so that no NaN reaches the report.
  Pose bodyPose = toPose(t.body.getWorldTransform());
  if (isFinite(bodyPose)) {
    t.lastFiniteBodyPose = bodyPose;
  } else {
    bodyPose = t.lastFiniteBodyPose;
  }
  contactForce.torquePoint = bodyPose.apply(t.options.force.torquePoint);
  diagnostics.lastWord.holdNodesShared = t.holdNodesShared;
  diagnostics.deformableNodeContacts = t.deformableNodeContacts;
  t.report.holdWrench.force = t.holdWrench.force;
  t.report.holdWrench.torque = t.holdWrench.torque - cross(bodyPose.translation, t.holdWrench.force);
  t.report.reaction = Wrench{};
  if (t.stepLength > 0) {
    const Vec3 force = toVec3(t.applied.linear) / Real(t.stepLength);
    const Vec3 torque = toVec3(t.applied.angular) / Real(t.stepLength) - cross(bodyPose.translation, force);
    if (isFinite(force) && isFinite(torque)) t.report.reaction = Wrench{force, torque};
  }

  for (const auto& statePointer : t.pairs) {
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
        t.report.excludedNodes.push_back({state.softBody, state.piece, node, check});
      }
    }

    // The piece's wrench is about the piece's origin; move the torque to the body's origin.
    const Pose piecePose = bodyPose * t.pieceTransforms[state.piece];
    const Wrench& wrench = state.response.wrench;
    t.report.wrench.force += wrench.force;
    t.report.wrench.torque +=
        wrench.torque + cross(piecePose.translation - bodyPose.translation, wrench.force);

    for (const FaceForce& face : state.force.faces) {
      contactForce.faces.push_back({state.softBody, state.piece, face});
      contactForce.force += face.force;
      contactForce.torque += cross(face.point - contactForce.torquePoint, face.force);
    }

    // What the soft solver left inside the tool, measured at the positions the step ended with.
    const ToolModel& model = t.pieces[state.piece];
    const btSoftBody& softBody = *state.softBody;
    for (const Contact& contact : state.detection.contacts) {
      t.report.contacts.push_back({&softBody, state.piece, contact});
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
  return t.report;
}

}  // namespace thintool
