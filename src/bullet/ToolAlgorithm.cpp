// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ToolAlgorithm.h"

#include "CollisionPass.h"
#include "PairState.h"
#include "SoftSurface.h"
#include "ToolReaction.h"
#include "ToolState.h"
#include "WriteCheck.h"
#include "tool/PieceMotion.h"

#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>
#include <thintool/core/Assert.h>

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyInternals.h>
#include <BulletSoftBody/btSoftBodySolvers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace thintool::detail {

namespace {

using Clock = std::chrono::steady_clock;

double microsecondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

// A contact with every field set, for resizing the soft body's list: Bullet leaves some of
// RContact's vectors unset, and resize() copies its fill value into each new slot.
const btSoftBody::RContact& blankContact() {
  static const btSoftBody::RContact blank = [] {
    btSoftBody::RContact contact;
    contact.t1 = contact.t2 = btVector3(0, 0, 0);
    return contact;
  }();
  return blank;
}

// Makes contact one of Bullet's soft solver that keeps a node on the positive side of a plane. PSolve_RContacts
// corrects x -= n·(dn + c4·dp) while dn <= 0, dn being the node's motion this step relative to
// the contact body's, (x - q - v_body·dt)·n. A body that moves the node onto the plane makes dn
// the node's distance in front of the plane: the contact stays idle while the node is in front,
// and with c4 = 0 puts it back on the plane when an iteration of the links or the pressure
// pushes it through; it never pulls it out further. The body has zero inverse mass, so the
// solver's impulses on it go nowhere (the tool's reaction comes from the projection), and it
// never reads the tool's own velocity, which after a jump of the tool is meaningless. contact is a
// blank one already in the soft body's list: Bullet's contact carries three
// btMultiBodyJacobianData, so building one aside and copying it in costs more than the rest.
void fillHoldContact(btSoftBody::RContact& contact, btSoftBody::Node& node, const NodeHold& hold,
                     btRigidBody& holdBody, btScalar timeStep) {
  const btVector3 normal = toBt(hold.normal);
  const btScalar inFront = normal.dot(node.m_x) + btScalar(hold.offset);
  const btVector3 onPlane = node.m_x - normal * btMax(inFront, btScalar(0));
  holdBody.setLinearVelocity((onPlane - node.m_q) / timeStep);
  holdBody.setAngularVelocity(btVector3(0, 0, 0));
  contact.m_cti.m_colObj = &holdBody;
  contact.m_cti.m_normal = normal;
  contact.m_cti.m_offset = btScalar(hold.offset);
  contact.m_node = &node;
  static const btMatrix3x3 zero(0, 0, 0, 0, 0, 0, 0, 0, 0);
  contact.m_c0 = ImpulseMatrix(timeStep, node.m_im, 0, zero, btVector3(0, 0, 0));
  contact.m_c1 = btVector3(0, 0, 0);
  contact.m_c2 = node.m_im * timeStep;
  // Frictionless (1) leaves the tangential motion alone; a node friction holds (0) is kept where
  // the response put it, which moves with the tool's surface.
  contact.m_c3 = hold.sticks ? 0 : 1;
  contact.m_c4 = 0;  // no positional term: the hold body already aims at the plane
}

// Appends a contact pass after the last link pass of the soft body's position solver, once. Bullet
// runs contacts before links in each iteration, so the links drag the held nodes: those under a
// dynamic tool that the force model carries, which then jitters on them (the force test's tool at
// rest moved at 0.4 m/s in Bullet's float64 build without the pass), and with another soft-body
// solver than ThinTool's, those friction holds to a grasping jaw (ThinTool's solver gives friction's
// holds alone their last say: SoftBodySolverImpl::solveHoldsLast). The extra pass gives the holds
// each iteration's last say. Penetration needs no such pass: the last word, after the solver,
// answers for it. The pass also re-solves that soft body's other contacts (with the ground, say)
// once more per iteration, which steadies the force on a tool pressing a body onto the ground (the
// Falcon demo's held plate: FalconDemoTest). A dynamic tool that takes the moved nodes' reactions
// does not get it: the holds having the last say against stiff links shook the bodies such tools
// touched, nodes at 82 to 541 m/s against a tool at 1 to 12 m/s (generated seeds 549, 1841, 2958,
// 4363, 5118, 7091), and a tool at rest on a pinned node needs only its stop to count Bullet's
// gyroscopic term (ToolReaction.cpp).
void makeContactsLast(btSoftBody& softBody) {
  auto& sequence = softBody.m_cfg.m_psequence;
  bool linksSeen = false;
  for (int k = 0; k < sequence.size(); ++k) {
    if (sequence[k] == btSoftBody::ePSolver::Linear) {
      linksSeen = true;
    } else if (sequence[k] == btSoftBody::ePSolver::RContacts) {
      linksSeen = false;  // a contact pass already follows every link pass so far
    }
  }
  if (linksSeen) {
    sequence.push_back(btSoftBody::ePSolver::RContacts);
  }
}

// Writes the corrections into the soft body: the moves, the solver's holds, and for a dynamic tool
// the reaction. dynamicBody, when not null, is a dynamic tool that takes the moved nodes' reaction.
// Returns the longest move written (m).
Real applyResponse(PairState& state, btSoftBody& softBody, DynamicBody dynamicBody, btScalar timeStep) {
  Real longestSquared = 0;
  const btScalar inverseStep = 1 / timeStep;
  const BodyVelocities toolBefore(dynamicBody);
  for (const NodeCorrection& correction : state.response.corrections) {
    longestSquared = std::max(longestSquared, lengthSquared(correction.displacement));
    THINTOOL_ASSERT(state.patch.nodeIds[correction.vertex] < static_cast<Index>(softBody.m_nodes.size()));
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(state.patch.nodeIds[correction.vertex])];
    const btVector3 displacement = toBt(correction.displacement);
    const btVector3 before = node.m_x;
    node.m_x += displacement;
    checkWrite(before, node.m_x, state.nonFiniteWrites);
    state.patch.positions[correction.vertex] += correction.displacement;
    if (dynamicBody && node.m_im > 0) {
      // The velocity Bullet's solve would have given the node where it was predicted to be. The
      // move gives the node m·|d|/dt whatever the two were closing at (a node the solver left inside
      // the skin, put back out, is the load of a resting contact: a lifted body's weight on the
      // fingers), so the exchange counts the move's own speed as closing speed at least.
      applyNodeReaction(dynamicBody, node.m_x, displacement, node.m_im, inverseStep,
                        (node.m_x - displacement - node.m_q) * inverseStep, /*closingAtMoveSpeed=*/true);
    }
  }
  if (dynamicBody && !state.response.corrections.empty()) {
    dynamicBody.activate();
  }
  toolBefore.check(state.nonFiniteWrites);
  const auto usable = [](const NodeHold& hold) { return isFinite(hold.normal) && std::isfinite(hold.offset); };
  const auto usableCount = std::count_if(state.holds.begin(), state.holds.end(), usable);
  int slot = softBody.m_rcontacts.size();
  // Both grow by doubling, as a std::vector does, so that a scene which holds a few more nodes than
  // ever before does not allocate again each step on its way there.
  const int needed = slot + static_cast<int>(usableCount);
  if (softBody.m_rcontacts.capacity() < needed) {
    softBody.m_rcontacts.reserve(std::max(needed, 2 * softBody.m_rcontacts.capacity()));
  }
  softBody.m_rcontacts.resize(needed, blankContact());
  if (state.holdBodies.size() < static_cast<std::size_t>(usableCount)) {
    const std::size_t grown = std::max(static_cast<std::size_t>(usableCount), 2 * state.holdBodies.size());
    while (state.holdBodies.size() < grown) {
      state.holdBodies.push_back(
          std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, nullptr)));
      state.holdBodies.back()->setUserPointer(const_cast<char*>(&kHoldBodyMark));
    }
  }
  Index holdsUsed = 0;
  state.firstHold = slot;
  for (const NodeHold& hold : state.holds) {
    if (!usable(hold)) {
      continue;
    }
    THINTOOL_ASSERT(state.patch.nodeIds[hold.vertex] < static_cast<Index>(softBody.m_nodes.size()));
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(state.patch.nodeIds[hold.vertex])];
    fillHoldContact(softBody.m_rcontacts[slot++], node, hold, *state.holdBodies[holdsUsed++], timeStep);
  }
  state.holdCount = static_cast<int>(holdsUsed);
  return std::sqrt(longestSquared);
}

// What Bullet's own soft–rigid algorithm does with the pair.
void handToStock(btSoftBody& softBody, const btCollisionObjectWrapper* toolWrap) {
  if (softBody.getSoftBodySolver() != nullptr) {
    softBody.getSoftBodySolver()->processCollision(&softBody, toolWrap);
  } else {
    softBody.defaultCollisionHandler(toolWrap);
  }
}

// Whether ThinTool's detection can give the deformable solve the pair's node contacts: a body with
// faces whose rigid contacts are the deformable ones (SDF_RD; Bullet's own node contacts come with
// SDF_RDN, with rigid bodies and multibody links alike).
bool feedsDeformableSolve(const btSoftBody& softBody) {
  return softBody.m_faces.size() > 0 && (softBody.m_cfg.collisions & btSoftBody::fCollision::SDF_RD) != 0;
}

// Bullet's own node contact's coefficient (CollideSDF_RS): the soft body's kDF times the rigid
// body's friction. Frictionless when either is not a number or negative.
Real pairFriction(const btSoftBody& softBody, const btCollisionObject& toolBody) {
  const Real coefficient = Real(softBody.m_cfg.kDF) * Real(toolBody.getFriction());
  return std::isfinite(coefficient) && coefficient > 0 ? coefficient : 0;
}

// The skin the pair keeps this step (ToolOptions::skinGrowthSpeed): in its first step, the
// closest gathered node's distance outside the piece at the start of the step, if that is within
// the skin; afterwards growing by growth a step, up to the skin.
Real pairSkin(PairState& state, const ToolModel& model, const Pose& startPose, Real skin, Real growth) {
  if (state.skinInEffect >= 0) {
    state.skinInEffect = std::min(skin, state.skinInEffect + growth);
    return state.skinInEffect;
  }
  Real closest = skin;
  const SoftPatch& patch = state.patch;
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    closest = std::min(closest, outsideDistance(model.planes, startPose.applyInverse(patch.previousPositions[v])));
  }
  state.skinInEffect = std::max(closest, Real(0));
  return state.skinInEffect;
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
      m_tool.state().pairState(*m_softBody, piece).separate();
    }
  }
}

// One piece's step against one soft body: what the stages read, and what they hand on.
struct ToolAlgorithm::PieceStep {
  PairState& state;
  btSoftBody& softBody;
  const btCollisionObject& toolBody;
  const ToolModel& model;
  Pose previousPose;
  Pose pose;
  bool swept = false;
  btScalar timeStep = 0;
  Real fullSkin = 0;  ///< ToolOptions::skin, or the soft body's margin (m)
  Real skin = 0;      ///< what the pair keeps this step (pairSkin), at most fullSkin (m)
  Index facesWalked = 0;  ///< soft faces the gather's walk met
  Real skinGrowthSpeed = 0;  ///< ToolOptions::skinGrowthSpeed (m/s)
  Pose inBody{};             ///< the piece on its body (Tool::pieceTransform)
  Real maxTurnPerSample = 0;  ///< a swept piece's arc in samples of this turn (rad); 0: the chord
  Clock::time_point start{};

  // What the core's stages read of the step.
  StepContext context() const {
    return {model, previousPose, pose, Real(timeStep), skin, skinGrowthSpeed, inBody, maxTurnPerSample};
  }
};

void ToolAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                     const btDispatcherInfo& /*dispatchInfo*/, btManifoldResult* /*resultOut*/) {
  const btCollisionObjectWrapper* softWrap = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* toolWrap = m_swapped ? body0 : body1;
  btSoftBody& softBody = *const_cast<btSoftBody*>(btSoftBody::upcast(softWrap->getCollisionObject()));
  const btCollisionObject& toolBody = m_tool.body();
  if (m_mode == Mode::Idle) {
    // A swept tool's own pair: its proxy's pair does ThinTool's work and counts the pairs Bullet
    // keeps, which are collided here, against the tool's shape as stock would.
    if (!ignores(softBody, toolBody) && stockReason(softBody) != StockReason::None) {
      handToStock(softBody, toolWrap);
    }
    return;
  }
  if (m_mode == Mode::OnePiece) {
    const Pose pose = toPose(toolWrap->getWorldTransform());
    PairState& state = *m_state;
    PieceStep step{state, softBody, toolBody, m_tool.state().pieces[state.piece],
                   state.hasPreviousPose ? state.previousPose : pose, pose};
    processPiece(step, toolWrap);
    return;
  }
  Pose bodyBefore;
  Pose bodyNow;
  m_tool.state().bodyMotion(bodyBefore, bodyNow);
  for (Index piece = 0; piece < m_tool.pieceCount(); ++piece) {
    PieceStep step{m_tool.state().pairState(softBody, piece), softBody, toolBody, m_tool.state().pieces[piece],
                   bodyBefore * m_tool.pieceTransform(piece), bodyNow * m_tool.pieceTransform(piece)};
    step.swept = true;
    step.inBody = m_tool.pieceTransform(piece);
    if (m_tool.state().options.sweptFollowsArc) {
      step.maxTurnPerSample = m_tool.state().options.separation.maxTurnPerSample;
    }
    processPiece(step, toolWrap);
  }
  if (DynamicBody dynamicBody = m_tool.state().dynamic()) {
    stopAtPinnedNodes(dynamicBody, softBody, softBody.m_sst.sdt, nullptr);
  }
}

void ToolAlgorithm::processPiece(PieceStep& step, const btCollisionObjectWrapper* toolWrap) {
  PairState& state = step.state;
  state.clearResults();
  state.live = true;

  if (ignores(step.softBody, step.toolBody)) {
    return;
  }
  state.stock = stockReason(step.softBody);
  if (state.stock != StockReason::None) {
    if (!step.swept) {
      handToStock(step.softBody, toolWrap);  // a swept tool's own pair does it (processCollision)
    }
    const bool feeds = state.stock == StockReason::DeformableWorld && step.swept &&
                       m_tool.state().options.bullet.deformableNodeContacts &&
                       feedsDeformableSolve(step.softBody);
    if (feeds && isFinite(step.pose) && isFinite(step.previousPose)) {
      detectForDeformableSolve(step);
    }
    return;
  }
  if (!isFinite(step.pose) || !isFinite(step.previousPose)) {
    state.invalidPose = true;
    if (!state.hasPreviousPose || !isFinite(state.previousPose)) {
      return;
    }
    // The tissue stays held where the tool last was, as if it had stood still for a step: skipping
    // the pair would let the soft body spring into the tool's space unopposed.
    step.previousPose = state.previousPose;
    step.pose = state.previousPose;
  }
  processValidPiece(step);
}

// The step's clock, length and skin growth, and the pair's buffers at the soft body's size.
void ToolAlgorithm::beginPieceStep(PieceStep& step) {
  step.start = Clock::now();
  step.timeStep = step.softBody.m_sst.sdt;
  step.skinGrowthSpeed = m_tool.state().options.skinGrowthSpeed;
  prepareBuffers(step);
}

// The stages, top to bottom; each reads what the ones before it left in the step and the pair.
void ToolAlgorithm::processValidPiece(PieceStep& step) {
  beginPieceStep(step);
  gather(step);
  detect(step);
  const auto detected = Clock::now();
  respond(step);
  if (step.swept) {
    rememberSweep(step);
  }
  write(step);
  releasePatch(step.state);
  step.state.detectionMicroseconds = microsecondsBetween(step.start, detected);
  step.state.responseMicroseconds = microsecondsBetween(detected, Clock::now());
}

// In the deformable world, swept detection alone: its node contacts go into Bullet's implicit solve
// in place of Bullet's own (DeformableBodySolver::setConstraints), and the last word follows the
// solve. Bullet predicts each node's end into m_q there, which the gather reads as the end.
void ToolAlgorithm::detectForDeformableSolve(PieceStep& step) {
  PairState& state = step.state;
  state.stock = StockReason::None;
  state.feedsDeformable = true;
  beginPieceStep(step);
  gather(step);
  detect(step);
  pairFrictionSettings(step);
  state.previousPose = step.pose;
  state.hasPreviousPose = true;
  rememberSweep(step);
  releasePatch(state);
  state.detectionMicroseconds = microsecondsBetween(step.start, Clock::now());
}

// The face tree, unless the pair scans the faces, and the pair's buffers at the soft body's size,
// whenever its faces change.
void ToolAlgorithm::prepareBuffers(PieceStep& step) {
  PairState& state = step.state;
  btSoftBody& softBody = step.softBody;
  const bool scans = step.swept && m_tool.state().options.bullet.scanFaces;
  if (!scans && ensureFaceTree(softBody) && m_tool.state().pass != nullptr) {
    m_tool.state().pass->recordUnfittedTree();
  }
  if (state.facesSeen == softBody.m_faces.size()) {
    return;
  }
  state.facesSeen = softBody.m_faces.size();
  readFaceCorners(softBody, state.faceCorners);
  state.patch.orientation = surfaceOrientation(softBody);
  state.patch.positions.reserve(softBody.m_nodes.size());
  state.patch.previousPositions.reserve(softBody.m_nodes.size());
  state.patch.checkedPositions.reserve(softBody.m_nodes.size());
  state.patch.inverseMasses.reserve(softBody.m_nodes.size());
  state.patch.nodeIds.reserve(softBody.m_nodes.size());
  state.patch.faces.reserve(softBody.m_faces.size());
  state.patch.faceIds.reserve(softBody.m_faces.size());
  state.detection.contacts.reserve(step.model.nodeCount());
  state.response.corrections.reserve(softBody.m_nodes.size());
  state.traversalStack.reserve(256);
  state.candidateFaces.reserve(softBody.m_faces.size());
  state.sides.resize(static_cast<Index>(softBody.m_nodes.size()), static_cast<Index>(softBody.m_faces.size()));
  state.lastPositions.resize(softBody.m_nodes.size());
  state.sweptNodes.reset(static_cast<Index>(softBody.m_nodes.size()));
}

// The soft faces near the piece into the pair's patch, and the skin the pair keeps this step.
void ToolAlgorithm::gather(PieceStep& step) {
  const ToolOptions& options = m_tool.state().options;
  PairState& state = step.state;
  btSoftBody& softBody = step.softBody;
  step.fullSkin = options.skin.value_or(Real(softBody.getCollisionShape()->getMargin()));
  // From here on, where the previous sweep left the nodes is the previous step's.
  if (step.swept) state.sweptNodes.beginStep();
  Aabb reach = transformedBounds(step.model.bounds, step.pose);
  if (step.swept) {
    reach.include(transformedBounds(step.model.bounds, step.previousPose));
  }
  // The force model counts a face with a node up to touchTolerance past the skin: the gather
  // takes those faces too, or whether a touching face counted would turn on whether the gather
  // found it, step by step (the hand feels that as chatter).
  if (options.force.enabled) reach = reach.expanded(options.force.touchTolerance);
  // Swept: the faces that meet the tool's whole motion during theirs. Scanned (BulletSettings::
  // scanFaces), every face's motion is read, where no tree exists. Walked, the tree is searched
  // first twice as far out as the soft nodes near the tool moved last step (the solver's pull
  // adds to the motion), or as the soft body moved as a whole this step, if farther.
  if (step.swept && m_tool.state().options.bullet.scanFaces && softBody.m_fdbvt.empty()) {
    step.facesWalked = gatherPatchByScan(softBody, reach.expanded(step.fullSkin), state);
  } else {
    const Real motionBound = step.swept ? std::max(2 * state.softReach, softBodyMotion(softBody, state)) : 0;
    const CollisionPass* pass = m_tool.state().pass;
    const Real nodeTravel = pass != nullptr ? pass->nodeTravel() : std::numeric_limits<Real>::infinity();
    step.facesWalked = gatherPatch(softBody, reach.expanded(step.fullSkin), motionBound,
                                   faceLeafSlack(softBody, nodeTravel), step.swept, state);
  }
  step.skin = pairSkin(state, step.model, step.previousPose, step.fullSkin,
                       options.skinGrowthSpeed * Real(step.timeStep));
}

// The contacts: swept over the step from where the sweep last left each node, or the paper's rays
// and checks at the step's end.
void ToolAlgorithm::detect(PieceStep& step) {
  PairState& state = step.state;
  if (step.swept) {
    SoftPatch& patch = state.patch;
    patch.checkedPositions.resize(patch.vertexCount());
    for (Index v = 0; v < patch.vertexCount(); ++v) {
      const Index id = patch.nodeIds[v];
      patch.checkedPositions[v] =
          state.sweptNodes.stampedLastStep(id) ? state.lastPositions[id] : patch.previousPositions[v];
    }
    detectSwept(step.context(), patch, state.sides, m_tool.state().sweptWorkspace,
                state.detection);
  } else {
    const SoftBodyRayQuery reverseQuery(step.softBody, state.traversalStack);
    DetectionInput input;
    input.filters = m_tool.state().options.filters;
    input.reverseRayLength = input.filters.reverseRayLength.value_or(
        length(toVec3(step.softBody.m_bounds[1] - step.softBody.m_bounds[0])));
    input.reverseQuery = &reverseQuery;
    detectContacts(step.context(), state.patch, input, state.history,
                   state.detection);
  }
  state.detection.counters.facesWalked = step.facesWalked;
}

// The corrections for the contacts; the pose becomes the start of the pair's next step.
void ToolAlgorithm::respond(PieceStep& step) {
  PairState& state = step.state;
  ResponseSettings response = m_tool.state().options.response;
  response.guardNodes = response.guardNodes && !step.swept;  // swept detection tests every node itself
  response.friction = pairFrictionSettings(step);
  computeResponse(step.context(), state.patch, state.detection.contacts, response,
                  state.response);
  state.previousPose = step.pose;
  state.hasPreviousPose = true;
}

// The tool's friction for the pair, the soft body's kDF times the tool body's friction with
// BulletSettings::frictionFromBodies, and the coefficients the pair's contacts in Bullet's solve
// take (its holds, or its node contacts in the deformable world): zero without friction.
FrictionSettings ToolAlgorithm::pairFrictionSettings(PieceStep& step) const {
  FrictionSettings friction = m_tool.state().options.response.friction;
  if (friction.enabled && m_tool.state().options.bullet.frictionFromBodies) {
    friction.staticCoefficient = pairFriction(step.softBody, step.toolBody);
    friction.kineticCoefficient = friction.staticCoefficient;
  }
  // A node that sticks goes along the chord of the tool point it sticks to, while the last word
  // reads a piece that turns more than one of its samples in a step along the arc: there the two
  // disagree on which side of the piece a stuck face went, and pushed it to and fro until the
  // rounds ran out with the face pierced (generated seeds 3461 and 7822 with friction: jaws and a
  // plate turning 78 to 166° a step through pinned sheets). Such a step of a kinematic tool is
  // frictionless. A dynamic tool's turn is the contacts' outcome, friction's among them: a plate
  // that friction's first steps set spinning, let go once it turned fast, reached 184 m/s (4884).
  const Real sample = m_tool.state().options.separation.maxTurnPerSample;
  if (friction.enabled && !m_tool.state().dynamic() &&
      PieceMotion(step.previousPose, step.pose, sample).samples() > 1) {
    friction.enabled = false;
  }
  step.state.holdStaticFriction = friction.enabled ? friction.staticCoefficient : 0;
  step.state.holdKineticFriction = friction.enabled ? friction.kineticCoefficient : 0;
  return friction;
}

// What the next sweep starts from: where this step leaves each node near the piece, and how far
// those nodes moved (the response's pushes included, which become next step's velocity): next step
// looks that much beyond the piece's swept box.
void ToolAlgorithm::rememberSweep(PieceStep& step) {
  PairState& state = step.state;
  const SoftPatch& patch = state.patch;
  state.softReach = 0;
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    state.softReach = std::max(state.softReach, length(patch.positions[v] - patch.previousPositions[v]));
    state.lastPositions[patch.nodeIds[v]] = patch.positions[v];
    state.sweptNodes.stamp(patch.nodeIds[v]);
  }
  for (const NodeCorrection& correction : state.response.corrections) {
    const Index v = correction.vertex;
    state.softReach =
        std::max(state.softReach, length(patch.positions[v] + correction.displacement - patch.previousPositions[v]));
    state.lastPositions[patch.nodeIds[v]] = patch.positions[v] + correction.displacement;
  }
}

// Into Bullet: the solver's holds, the moves, a dynamic tool's reaction, and the force model.
void ToolAlgorithm::write(PieceStep& step) {
  const ToolOptions& options = m_tool.state().options;
  PairState& state = step.state;
  DynamicBody dynamicBody = m_tool.state().dynamic();
  const bool forceReacts = options.force.enabled && options.force.applyToDynamicTool;
  if (options.response.kind == ResponseKind::Constraint && options.bullet.holdInSolver) {
    computeHolds(step.context(), state.patch, step.swept, state.response,
                 state.holds);
    // The holds' last say in each position iteration. Under a dynamic tool that the force model
    // carries, Bullet's whole contact stage once more after the links: the body's other contacts
    // (the ground it is pressed onto) then hold too, and the force the tool feels stays steady.
    // For friction alone, thintool::SoftBodySolver gives it to the holds alone (its solve has begun
    // the step when the tool's step length is known). The whole stage's other contacts are only
    // appended once the response has moved a node: a pressure body on the ground shook at twice
    // stock's speed with it while a tool was merely near. Friction is the pair's in this step
    // (pairFrictionSettings): a needle turning 124° a step, frictionless in every step but its
    // first, kept the holds' last say and pierced a sheet (generated seed 623 with friction).
    if (dynamicBody && forceReacts) {
      if (!state.response.corrections.empty()) makeContactsLast(step.softBody);
    } else if (state.holdStaticFriction > 0 || state.holdKineticFriction > 0) {
      if (m_tool.state().stepLength > 0) {
        state.holdsLast = true;
      } else if (!state.response.corrections.empty()) {
        makeContactsLast(step.softBody);
      }
    }
  }
  const Real moved =
      applyResponse(state, step.softBody, forceReacts ? DynamicBody() : dynamicBody, step.timeStep);
  // A dynamic tool's holds carry friction in the soft solve, which follows the tool's surface where
  // each held node now is. A kinematic tool's do not: it is driven into the tissue by its pose,
  // which gives the response's friction its normal move each step, and friction in the solve made
  // the clamp's held vessel rock (its load varying by 121 % peak to peak at the hand, against 14 %,
  // examples/clamp_demo --session --vessel).
  state.holdSurfaceMoves.clear();
  if (dynamicBody && (state.holdStaticFriction > 0 || state.holdKineticFriction > 0)) {
    for (int k = 0; k < state.holdCount; ++k) {
      const Vec3 at = toVec3(step.softBody.m_rcontacts[state.firstHold + k].m_node->m_x);
      state.holdSurfaceMoves.push_back(at - step.previousPose.apply(step.pose.applyInverse(at)));
    }
  }
  if (m_tool.state().pass != nullptr) {
    m_tool.state().pass->recordMoves(moved);
  }
  if (options.force.enabled) {
    computeForces(step, forceReacts ? dynamicBody : DynamicBody());
  }
  // The soft solver's end-of-step stop at pinned nodes comes after the tool has moved; the
  // reactions above and the tool's own forces come before it moves again, and would otherwise carry
  // it past a pinned node it rests on. The tool is still where the step began: a dynamic tool's
  // sweep starts there, and an unswept piece is taken there.
  if (dynamicBody && !forceReacts) {
    state.pinnedStopPose = step.swept ? step.previousPose : step.pose;
    state.stopsAtPinned = true;
    // A swept tool's pieces stop it together once all of them have reacted (processCollision).
    if (!step.swept) stopAtPinnedNodes(dynamicBody, step.softBody, step.timeStep, &state);
  }
}

// The pinned nodes of one pair's patch stop the dynamic tool short of them, or, without a pair, those
// of every pair of the tool with the soft body that stops it this step: a swept tool's pieces stop
// it together, after every piece has reacted on it. One jaw's reaction turned a pair of jaws into a
// pinned node that the other jaw's stop had kept them short of (generated seed 29819).
void ToolAlgorithm::stopAtPinnedNodes(DynamicBody& tool, const btSoftBody& softBody, btScalar timeStep,
                                      const PairState* single) {
  const auto forEachPinned = [&](const auto& visit) {
    const auto visitPair = [&](const PairState& state) {
      if (!state.stopsAtPinned || state.softBody != &softBody) return;
      const SoftPatch& patch = state.patch;
      for (Index v = 0; v < patch.vertexCount(); ++v) {
        if (!(patch.inverseMasses[v] > 0)) visit(m_tool.state().pieces[state.piece], state.pinnedStopPose, patch.positions[v]);
      }
    };
    if (single != nullptr) {
      visitPair(*single);
      return;
    }
    for (const auto& pair : m_tool.state().pairs) visitPair(*pair);
  };
  const BodyVelocities before(tool);
  stopShortOfPinnedNodes(tool, forEachPinned, Real(1) / Real(timeStep), true);
  // Counted with the soft body's first pair, whichever pieces stopped the tool.
  for (const auto& pair : m_tool.state().pairs) {
    if (pair->softBody == &softBody) {
      before.check(pair->nonFiniteWrites);
      break;
    }
  }
}

void ToolAlgorithm::computeForces(PieceStep& step, DynamicBody reactingBody) {
  PairState& state = step.state;
  btSoftBody& softBody = step.softBody;
  const ForceSettings& settings = m_tool.state().options.force;
  const RestShape& rest = m_tool.state().restShape(softBody);
  if (settings.measure == DeformationMeasure::Indentation) {
    state.anchorPositions.clear();
    for (Index node : rest.anchors()) {
      state.anchorPositions.push_back(toVec3(softBody.m_nodes[static_cast<int>(node)].m_x));
    }
    state.rigidFit = fitRigidMotion(rest, state.anchorPositions, state.rigidFit);
  }
  state.force.history.resize(static_cast<Index>(softBody.m_faces.size()));
  computeContactForces(step.context(), state.patch, state.detection.contacts,
                       {settings, rest, state.rigidFit}, state.force);
  if (!reactingBody) {
    return;
  }
  const BodyVelocities before(reactingBody);
  for (const FaceForce& face : state.force.faces) {
    if (isFinite(face.force) && isFinite(face.point) && lengthSquared(face.force) > 0) {
      reactingBody.applyImpulse(toBt(face.force * step.timeStep), toBt(face.point));
      reactingBody.activate();
    }
  }
  before.check(state.nonFiniteWrites);
}

}  // namespace thintool::detail
