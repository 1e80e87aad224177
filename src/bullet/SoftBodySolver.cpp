// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/SoftBodySolver.h>

#include "PairState.h"
#include "SoftBodySolverImpl.h"
#include "SoftSurface.h"
#include "ToolReaction.h"
#include "ToolState.h"
#include "WriteCheck.h"
#include "geometry/SolidAngle.h"

#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>
#include <thintool/core/Assert.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyInternals.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

namespace thintool {

namespace {

// A moved node's reaction on the dynamic tool that moved it by displacement, the node having moved
// at solvedVelocity before. Squeezed between the tool and a body that does not yield (backing, a
// contact of Bullet's own), the node stops the tool as that body would.
void reactOnTool(detail::DynamicBody& tool, const btSoftBody& softBody, const btSoftBody::Node& node,
                 const btSoftBody::RContact* backing, const btVector3& displacement, const btVector3& solvedVelocity) {
  if (backing == nullptr || backing->m_cti.m_normal.dot(displacement) >= 0) {
    detail::applyNodeReaction(tool, node.m_x, displacement, node.m_im, softBody.m_sst.isdt, solvedVelocity);
    return;
  }
  const btRigidBody* backingBody = btRigidBody::upcast(backing->m_cti.m_colObj);
  const btVector3 backingVelocity =
      backingBody != nullptr ? backingBody->getVelocityInLocalPoint(node.m_x - backingBody->getCenterOfMassPosition())
                             : btVector3(0, 0, 0);
  detail::applyNodeReaction(tool, node.m_x, displacement, 0, softBody.m_sst.isdt, backingVelocity);
}

// Adds force (N, on the tool) at point (world) to the tool's hold wrench, whose torque is about the
// world's origin.
void addToHoldWrench(detail::ToolState& tool, const Vec3& point, const Vec3& force) {
  tool.holdWrench.force += force;
  tool.holdWrench.torque += cross(point, force);
}

// Adds to a tool's hold wrench the force of a hold that undid moveUndone of the node's motion in a
// contact stage: the hold's impulse is m·moveUndone/dt, the force over the step that impulse over dt.
void addHoldForce(detail::ToolState& tool, const btSoftBody::Node& node, const btVector3& moveUndone,
                  double inverseStepSquared) {
  if (!(node.m_im > 0)) return;
  const Vec3 force = toVec3(moveUndone) * (inverseStepSquared / double(node.m_im));
  if (!isFinite(force)) return;
  addToHoldWrench(tool, toVec3(node.m_x), force);
}

// Everything the piece can reach during the step: its boxes at the arc's samples, grown by how far
// a point of the piece strays from the straight line between two samples, r·(1 − cos(θ/2)) for a
// point r from the body's origin and a turn θ between samples.
Aabb sweptBounds(const Aabb& local, const PieceMotion& motion) {
  Aabb box;
  Real radius = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                 (corner & 4) ? local.max.z : local.min.z};
    radius = std::max(radius, length(motion.start().apply(p) - motion.bodyStart().translation));
  }
  for (int k = 0; k <= motion.samples(); ++k) {
    box.include(transformedBounds(local, motion.at(Real(k) / Real(motion.samples()))));
  }
  return box.expanded(radius * (1 - std::cos(motion.turn() / (2 * motion.samples()))));
}

// Whether a node's move from a to b meets the box: the box of the move does.
bool segmentMeets(const Aabb& box, const btVector3& a, const btVector3& b) {
  for (int axis = 0; axis < 3; ++axis) {
    if (Real(btMax(a[axis], b[axis])) < box.min[axis] || Real(btMin(a[axis], b[axis])) > box.max[axis]) return false;
  }
  return true;
}

// The nearest of Bullet's scalars at or below v, and at or above it.
btScalar roundedDown(Real v) {
  const auto rounded = static_cast<btScalar>(v);
  return Real(rounded) > v ? std::nextafter(rounded, -std::numeric_limits<btScalar>::infinity()) : rounded;
}
btScalar roundedUp(Real v) {
  const auto rounded = static_cast<btScalar>(v);
  return Real(rounded) < v ? std::nextafter(rounded, std::numeric_limits<btScalar>::infinity()) : rounded;
}

// A free node's shares of its body's motion at velocity v: ½·m·v² and m·v. One definition for
// the pass over the nodes and for the shares the solve keeps, so that both sum to the same bits.
double kineticShareOf(const btVector3& v, double m) { return 0.5 * m * double(v.length2()); }
btVector3 momentumShareOf(const btVector3& v, double m) { return v * btScalar(m); }

// The motion of a soft body's free nodes, each at the velocity velocityOf gives it.
template <class VelocityOf>
detail::BodyMotion motionOf(const btSoftBody& softBody, VelocityOf velocityOf) {
  detail::BodyMotion motion;
  for (int i = 0; i < softBody.m_nodes.size(); ++i) {
    const btSoftBody::Node& node = softBody.m_nodes[i];
    if (!(node.m_im > 0)) continue;
    const double m = 1 / double(node.m_im);
    const btVector3 velocity = velocityOf(node);
    motion.mass += m;
    motion.kinetic += kineticShareOf(velocity, m);
    motion.momentum += momentumShareOf(velocity, m);
  }
  return motion;
}

// The dynamic tool that takes the last word's reactions, or nullptr: none when the tool is not
// dynamic, or when its force model is what reacts on it (ForceSettings::applyToDynamicTool), as for
// the collision stage's own moves.
detail::DynamicBody reactingBody(const detail::ToolState& tool) {
  const ForceSettings& force = tool.options.force;
  return force.enabled && force.applyToDynamicTool ? detail::DynamicBody() : tool.dynamic();
}

// The speed of the tool's fastest corner over the step (m/s).
double fastestCorner(const Tool& tool, const Pose& before, const Pose& now, Real inverseStep) {
  double fastest = 0;
  for (Index p = 0; p < tool.pieceCount(); ++p) {
    const Pose start = before * tool.pieceTransform(p);
    const Pose end = now * tool.pieceTransform(p);
    for (const Vec3& corner : tool.piece(p).mesh.vertices) {
      fastest = std::max(fastest, double(length(end.apply(corner) - start.apply(corner)) * inverseStep));
    }
  }
  return std::isfinite(fastest) ? fastest : 0;
}

// The free node a correction of the pair moved, or nullptr (pinned, or no longer in the body).
const btSoftBody::Node* movedNode(const btSoftBody& softBody, const detail::PairState& pair,
                                  const NodeCorrection& correction) {
  const Index id = pair.patch.nodeIds[correction.vertex];
  if (id >= static_cast<Index>(softBody.m_nodes.size())) return nullptr;
  const btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(id)];
  return node.m_im > 0 ? &node : nullptr;
}

// The free node of the pair's k-th hold in this step, or nullptr (pinned, or the hold's contact
// since replaced), by the same checks the solve's holds pass.
const btSoftBody::Node* heldNode(const btSoftBody& softBody, const detail::PairState& pair, int k) {
  const int contact = pair.firstHold + k;
  if (contact >= softBody.m_rcontacts.size() ||
      softBody.m_rcontacts[contact].m_cti.m_colObj != pair.holdBodies[static_cast<std::size_t>(k)].get()) {
    return nullptr;
  }
  const btSoftBody::Node* node = softBody.m_rcontacts[contact].m_node;
  return node != nullptr && node->m_im > 0 ? node : nullptr;
}

// Every face's three edges, each as its nodes' indices (lower first), sorted.
std::vector<std::pair<Index, Index>> sortedFaceEdges(const btSoftBody& softBody) {
  const int faceCount = softBody.m_faces.size();
  std::vector<std::pair<Index, Index>> edges;
  if (faceCount == 0) return edges;
  const btSoftBody::Node* first = &softBody.m_nodes[0];
  edges.reserve(static_cast<std::size_t>(faceCount) * 3);
  for (int f = 0; f < faceCount; ++f) {
    const btSoftBody::Face& face = softBody.m_faces[f];
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<Index>(face.m_n[k] - first);
      const auto b = static_cast<Index>(face.m_n[(k + 1) % 3] - first);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// Whether every edge of the faces (sortedFaceEdges) is shared by exactly two faces. Run when the
// topology is new to the solver or has changed, never in a step that only moves nodes.
bool surfaceIsClosed(const std::vector<std::pair<Index, Index>>& edges) {
  if (edges.empty()) return false;
  for (std::size_t i = 0; i < edges.size(); i += 2) {
    const bool pair = i + 1 < edges.size() && edges[i] == edges[i + 1];
    if (!pair || (i + 2 < edges.size() && edges[i + 2] == edges[i])) return false;
  }
  return true;
}

// Whether every edge of the body's faces (sortedFaceEdges) is also a link that is not a bending
// one. Run with surfaceIsClosed.
bool edgesAreLinks(const btSoftBody& softBody, const std::vector<std::pair<Index, Index>>& edges) {
  if (edges.empty()) return false;
  const btSoftBody::Node* first = &softBody.m_nodes[0];
  std::vector<std::pair<Index, Index>> links;
  links.reserve(static_cast<std::size_t>(softBody.m_links.size()));
  for (int l = 0; l < softBody.m_links.size(); ++l) {
    const btSoftBody::Link& link = softBody.m_links[l];
    if (link.m_bbending) continue;
    const auto a = static_cast<Index>(link.m_n[0] - first);
    const auto b = static_cast<Index>(link.m_n[1] - first);
    links.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(links.begin(), links.end());
  return std::all_of(edges.begin(), edges.end(), [&](const std::pair<Index, Index>& edge) {
    return std::binary_search(links.begin(), links.end(), edge);
  });
}

// The generalised winding number of point p in the body's surface, each node where positionOf puts
// it (geometry/SolidAngle.h): near ±1 inside a closed surface, near 0 outside.
template <typename PositionOf>
Real windingNumber(const btSoftBody& softBody, const Vec3& p, const PositionOf& positionOf) {
  const btSoftBody::Node* first = softBody.m_nodes.size() > 0 ? &softBody.m_nodes[0] : nullptr;
  Real total = 0;
  for (int f = 0; f < softBody.m_faces.size(); ++f) {
    const btSoftBody::Face& face = softBody.m_faces[f];
    total += triangleSolidAngle(positionOf(static_cast<Index>(face.m_n[0] - first)) - p,
                                positionOf(static_cast<Index>(face.m_n[1] - first)) - p,
                                positionOf(static_cast<Index>(face.m_n[2] - first)) - p);
  }
  return total / (4 * kPi);
}

}  // namespace

SoftBodySolver::SoftBodySolver(CollisionConfiguration& configuration)
    : m_impl(std::make_unique<detail::SoftBodySolverImpl>(configuration, m_softBodySet)) {}

SoftBodySolver::~SoftBodySolver() = default;

void SoftBodySolver::solveConstraints(btScalar timeStep) { m_impl->solveConstraints(timeStep); }

void SoftBodySolver::predictMotion(btScalar timeStep) { m_impl->predictMotion(timeStep); }

namespace detail {

SoftBodySolverImpl::SoftBodySolverImpl(CollisionConfiguration& configuration,
                                       btAlignedObjectArray<btSoftBody*>& softBodySet, bool deformable)
    : m_configuration(configuration), m_softBodySet(softBodySet), m_deformable(deformable) {}

bool SoftBodySolverImpl::actsOn(const btSoftBody& body) const {
  const StockReason reason = detail::stockReason(body);
  return detail::lastWordActsOn(reason) || (m_deformable && reason == StockReason::DeformableWorld);
}

void SoftBodySolverImpl::solveSoftBodies() {
  // As btDefaultSoftBodySolverImpl::solveConstraints: every active body of the solver's set, in order.
  // ThinTool's copy of Bullet's solve serves a body that tools hold, to measure the holds, and one
  // the last word will look at, to survey it in the solve's last pass over its nodes.
  for (int i = 0; i < m_softBodySet.size(); ++i) {
    btSoftBody& body = *m_softBodySet[i];
    if (!body.isActive()) continue;
    // A guarded body's nodes move no farther in the solve than the guard's speed bound allows
    // over the step: bounding only the velocity the solve leaves would let a node jump across the
    // step and keep the jump. Only where the last word follows, which puts back on its side a node
    // that the shorter move leaves in a tool (the response's own push is part of the move).
    const BodyEnergy& energy = m_energy[static_cast<std::size_t>(i)];
    const bool shorten = energy.predicted >= 0 && energy.lastWordFollows;
    if (collectHolds(body) || lastWordReaches(body) || shorten) {
      const btScalar longestMove = shorten ? btScalar(fastestAllowed(energy)) * body.m_sst.sdt : BT_LARGE_FLOAT;
      solveInStages(body, longestMove, energy.predicted >= 0);
    } else {
      body.solveConstraints();
    }
  }
}

bool SoftBodySolverImpl::lastWordReaches(const btSoftBody& body) const {
  if (!m_hasStepReach) return false;
  return std::any_of(m_active.begin(), m_active.end(), [&](const Tool* tool) {
    return !detail::ignores(body, tool->body()) && actsOn(body);
  });
}

bool SoftBodySolverImpl::collectHolds(btSoftBody& body) {
  m_held.clear();
  m_holdContacts.clear();
  m_holdsLast = false;
  m_sharedHolds.clear();
  m_reachingHolds.clear();
  const int nodeCount = body.m_nodes.size();
  if (m_heldOfNode.size() < static_cast<std::size_t>(nodeCount)) m_heldOfNode.resize(nodeCount, -1);
  const btSoftBody::Node* const firstNode = nodeCount > 0 ? &body.m_nodes[0] : nullptr;
  for (Tool* tool : m_configuration.tools()) {
    for (const auto& pair : tool->state().pairs) {
      const detail::PairState& state = *pair;
      if (state.softBody != &body || state.holdCount == 0 ||
          state.firstHold + state.holdCount > body.m_rcontacts.size()) {
        continue;
      }
      const std::optional<Real>& planeReach = tool->state().options.bullet.holdPlaneReach;
      Pose piecePose;
      Real reach = 0;
      if (planeReach.has_value()) {
        piecePose = toPose(tool->body().getWorldTransform()) * tool->pieceTransform(state.piece);
        reach = std::max(state.skinInEffect, Real(0)) * (1 + *planeReach);
      }
      for (int k = 0; k < state.holdCount; ++k) {
        const btSoftBody::RContact& contact = body.m_rcontacts[state.firstHold + k];
        // Contacts of an earlier step, since replaced: not this pair's holds.
        if (contact.m_cti.m_colObj != state.holdBodies[static_cast<std::size_t>(k)].get()) break;
        m_holdContacts.push_back(state.firstHold + k);
        m_holdsLast = m_holdsLast || state.holdsLast;
        // A hold with friction keeps a grasped node with the jaw wherever it is: never limited.
        if (planeReach.has_value() && contact.m_c3 > 0) {
          m_reachingHolds.push_back(
              {state.firstHold + k, &tool->piece(state.piece), piecePose, reach, contact.m_cti.m_normal});
        }
        const int node = static_cast<int>(contact.m_node - firstNode);
        int& entry = m_heldOfNode[static_cast<std::size_t>(node)];
        if (entry < 0) {
          entry = static_cast<int>(m_held.size());
          m_held.push_back({node, tool, false, false, btVector3(0, 0, 0), btVector3(0, 0, 0)});
          HeldNode& added = m_held.back();
          // Friction where the pair gave its holds the tool's surface motion (a dynamic tool's).
          if (static_cast<std::size_t>(k) < state.holdSurfaceMoves.size() && contact.m_c3 > 0) {
            added.staticFriction = btScalar(state.holdStaticFriction);
            added.kineticFriction = btScalar(state.holdKineticFriction);
            added.normal = contact.m_cti.m_normal;
            added.surfaceMove = toBt(state.holdSurfaceMoves[static_cast<std::size_t>(k)]);
          }
        } else if (m_held[static_cast<std::size_t>(entry)].tool != tool) {
          m_held[static_cast<std::size_t>(entry)].severalTools = true;
        }
        m_sharedHolds.push_back({state.firstHold + k, entry, tool});
      }
    }
  }
  if (m_held.empty()) return false;
  for (int c = 0; c < body.m_rcontacts.size(); ++c) {
    const btSoftBody::RContact& contact = body.m_rcontacts[c];
    const int entry = m_heldOfNode[static_cast<std::size_t>(contact.m_node - firstNode)];
    if (entry < 0) continue;
    HeldNode& held = m_held[static_cast<std::size_t>(entry)];
    if (contact.m_cti.m_colObj == nullptr || contact.m_cti.m_colObj->getUserPointer() != &detail::kHoldBodyMark) {
      held.bulletContact = true;
    }
  }
  const auto notShared = [&](const SharedHold& hold) {
    const HeldNode& held = m_held[static_cast<std::size_t>(hold.held)];
    return !held.severalTools || held.bulletContact;
  };
  m_sharedHolds.erase(std::remove_if(m_sharedHolds.begin(), m_sharedHolds.end(), notShared), m_sharedHolds.end());
  std::sort(m_sharedHolds.begin(), m_sharedHolds.end(),
            [](const SharedHold& a, const SharedHold& b) { return a.contact < b.contact; });
  for (const HeldNode& held : m_held) {
    m_heldOfNode[static_cast<std::size_t>(held.node)] = -1;
    if (held.bulletContact) ++held.tool->state().holdNodesShared;
  }
  return true;
}

namespace {

// A hold as PSolve_RContacts solves it, at full stiffness, for its node at position: the impulse,
// zero while the node leaves the plane. The hold's body has zero inverse mass and no spin, its
// velocity aimed at the plane (fillHoldContact in ToolAlgorithm.cpp), so the impulse moves the
// node alone, by -impulse·c2.
btVector3 holdImpulse(const btSoftBody::RContact& contact, const btVector3& position, btScalar dt, btScalar margin) {
  const auto& holdBody = static_cast<const btRigidBody&>(*contact.m_cti.m_colObj);
  const btVector3 relative = (position - contact.m_node->m_q) - holdBody.getLinearVelocity() * dt;
  const btVector3& normal = contact.m_cti.m_normal;
  const btScalar approach = relative.dot(normal);
  if (approach > SIMD_EPSILON) return btVector3(0, 0, 0);
  const btScalar depth = btMin(position.dot(normal) + contact.m_cti.m_offset, margin);
  const btVector3 tangential = relative - normal * approach;
  return contact.m_c0 * (relative - tangential * contact.m_c3 + normal * (depth * contact.m_c4));
}

}  // namespace

void SoftBodySolverImpl::replaySharedHolds(btSoftBody& body, double inverseStepSquared) {
  // Each hold from where the stage found the node, so that each tool gets the part of the move its
  // own hold made.
  const btScalar dt = body.m_sst.sdt;
  const btScalar margin = body.getCollisionShape()->getMargin();
  for (HeldNode& held : m_held) held.replayed = held.before;
  for (SharedHold& shared : m_sharedHolds) {
    HeldNode& held = m_held[static_cast<std::size_t>(shared.held)];
    const btSoftBody::RContact& contact = body.m_rcontacts[shared.contact];
    const btVector3 move = holdImpulse(contact, held.replayed, dt, margin) * contact.m_c2;
    held.replayed -= move;
    shared.pushed -= move;
    addHoldForce(shared.tool->state(), body.m_nodes[held.node], move, inverseStepSquared);
  }
}

void SoftBodySolverImpl::solveHoldsLast(btSoftBody& body) {
  // The holds alone: a pass of Bullet's whole contact stage after the links re-solved the body's
  // other contacts too, and a pressure body shaking on the ground by itself then shook more than
  // twice as fast (generated seeds 1193, 2148, 3220, 4092, 4450, 5044, 7343, 9903 with friction).
  const btScalar dt = body.m_sst.sdt;
  const btScalar margin = body.getCollisionShape()->getMargin();
  for (const int c : m_holdContacts) {
    const btSoftBody::RContact& contact = body.m_rcontacts[c];
    contact.m_node->m_x -= holdImpulse(contact, contact.m_node->m_x, dt, margin) * contact.m_c2;
  }
}

void SoftBodySolverImpl::applyHoldFriction(btSoftBody& body, double inverseStepSquared) {
  for (HeldNode& held : m_held) {
    if (held.severalTools || held.bulletContact || !(held.staticFriction > 0 || held.kineticFriction > 0)) continue;
    btSoftBody::Node& node = body.m_nodes[held.node];
    const btScalar pushed = (node.m_x - held.before).dot(held.normal);
    if (!(pushed > 0)) continue;  // no normal force in this stage: no friction
    const btVector3 relative = node.m_x - node.m_q - held.surfaceMove;
    const btVector3 tangential = relative - held.normal * relative.dot(held.normal);
    const btScalar slip = tangential.length();
    if (!(slip > 0) || !std::isfinite(slip)) continue;
    const btVector3 move = slip <= held.staticFriction * pushed
                               ? -tangential
                               : tangential * -btMin(btScalar(1), held.kineticFriction * pushed / slip);
    const btVector3 before = node.m_x;
    node.m_x += move;
    detail::checkWrite(before, node.m_x, held.tool->state().lastWord.nonFiniteWrites);
    addHoldForce(held.tool->state(), node, -move, inverseStepSquared);
    held.pushed += move;
  }
}

void SoftBodySolverImpl::reactToHolds(btSoftBody& body) {
  const btScalar inverseStep = body.m_sst.isdt;
  const auto react = [&](Tool& tool, const btSoftBody::Node& node, const btVector3& pushed) {
    detail::DynamicBody dynamicTool = reactingBody(tool.state());
    if (!dynamicTool || pushed.isZero()) return;
    const detail::BodyVelocities before(dynamicTool);
    // The node's velocity had the holds not pushed it: the solve's, less their push.
    const btVector3 unpushedVelocity = (node.m_x - pushed - node.m_q) * inverseStep;
    if (detail::applyNodeReaction(dynamicTool, node.m_x, pushed, node.m_im, inverseStep, unpushedVelocity) > 0) {
      dynamicTool.activate();
    }
    before.check(tool.state().lastWord.nonFiniteWrites);
  };
  for (const HeldNode& held : m_held) {
    if (held.severalTools || held.bulletContact) continue;
    react(*held.tool, body.m_nodes[held.node], held.pushed);
  }
  for (const SharedHold& shared : m_sharedHolds) {
    react(*shared.tool, body.m_nodes[m_held[static_cast<std::size_t>(shared.held)].node], shared.pushed);
  }
}

void SoftBodySolverImpl::limitHoldReach(btSoftBody& body) {
  for (const ReachingHold& hold : m_reachingHolds) {
    btSoftBody::RContact& contact = body.m_rcontacts[hold.contact];
    const btVector3& x = contact.m_node->m_x;
    const btVector3 onPlane = x - hold.normal * (hold.normal.dot(x) + contact.m_cti.m_offset);
    const bool backed = outsideDistance(hold.piece->planes, hold.piecePose.applyInverse(toVec3(onPlane))) < hold.reach;
    contact.m_cti.m_normal = backed ? hold.normal : btVector3(0, 0, 0);
  }
}

bool SoftBodySolverImpl::hasLivePair(const Tool& tool, const btSoftBody& body) {
  return std::any_of(tool.state().pairs.begin(), tool.state().pairs.end(),
                     [&](const auto& pair) { return pair->softBody == &body && pair->live; });
}

bool SoftBodySolverImpl::guardingToolNear(const btSoftBody& body) const {
  return std::any_of(m_configuration.tools().begin(), m_configuration.tools().end(), [&](const Tool* tool) {
    return tool->state().options.energyGuard.enabled && hasLivePair(*tool, body);
  });
}

template <typename Report>
void SoftBodySolverImpl::reportToToolsNear(const btSoftBody& body, const Report& report) {
  for (Tool* tool : m_configuration.tools()) {
    if (hasLivePair(*tool, body)) report(tool->state().lastWord);
  }
}

double SoftBodySolverImpl::fastestAllowed(const BodyEnergy& energy) {
  return std::max(energy.speedFactor * std::max(1.0, energy.toolAtMovedNodes), energy.predictedFastest);
}

void SoftBodySolverImpl::solveInStages(btSoftBody& body, btScalar longestMove, bool guarded) {
  // Bullet 3.24's btSoftBody::solveConstraints (btSoftBody.cpp), stage for stage and in its
  // arithmetic, so that a body solved here moves exactly as Bullet would move it.
  body.applyClusters(false);
  btScalar longestEdgeSquared = 0;
  for (int i = 0; i < body.m_links.size(); ++i) {
    btSoftBody::Link& link = body.m_links[i];
    link.m_c3 = link.m_n[1]->m_q - link.m_n[0]->m_q;
    const btScalar lengthSquared = link.m_c3.length2();
    link.m_c2 = 1 / (lengthSquared * link.m_c0);
    if (!link.m_bbending) longestEdgeSquared = btMax(longestEdgeSquared, lengthSquared);
  }
  for (int i = 0; i < body.m_anchors.size(); ++i) {
    btSoftBody::Anchor& anchor = body.m_anchors[i];
    const btVector3 arm = anchor.m_body->getWorldTransform().getBasis() * anchor.m_local;
    anchor.m_c0 = ImpulseMatrix(body.m_sst.sdt, anchor.m_node->m_im, anchor.m_body->getInvMass(),
                                anchor.m_body->getInvInertiaTensorWorld(), arm);
    anchor.m_c1 = arm;
    anchor.m_c2 = body.m_sst.sdt * anchor.m_node->m_im;
    anchor.m_body->activate();
  }
  btSoftBody::Config& config = body.m_cfg;
  if (config.viterations > 0) {
    for (int iteration = 0; iteration < config.viterations; ++iteration) {
      for (int stage = 0; stage < config.m_vsequence.size(); ++stage) {
        btSoftBody::getSolver(config.m_vsequence[stage])(&body, 1);
      }
    }
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      btSoftBody::Node& node = body.m_nodes[i];
      node.m_x = node.m_q + node.m_v * body.m_sst.sdt;
    }
  }
  if (config.piterations > 0) {
    // A hold moves its node by -impulse·m⁻¹·dt and gives the tool's stand-in body +impulse: the
    // force on the tool over the step is Σ m·(before - after)/dt² over the contact stages.
    const double inverseStepSquared = double(body.m_sst.isdt) * double(body.m_sst.isdt);
    // Each contact stage measured: Bullet's own (all of the body's contacts), and where the holds
    // need the last say, the holds alone after the links (solveHoldsLast).
    const auto measuredContactStage = [&](const auto& solve) {
      for (HeldNode& held : m_held) held.before = body.m_nodes[held.node].m_x;
      limitHoldReach(body);
      solve();
      for (HeldNode& held : m_held) {
        const btSoftBody::Node& node = body.m_nodes[held.node];
        if (held.severalTools || held.bulletContact) continue;
        addHoldForce(held.tool->state(), node, held.before - node.m_x, inverseStepSquared);
        held.pushed += node.m_x - held.before;
      }
      if (!m_sharedHolds.empty()) replaySharedHolds(body, inverseStepSquared);
      applyHoldFriction(body, inverseStepSquared);
    };
    for (int iteration = 0; iteration < config.piterations; ++iteration) {
      const btScalar fraction = iteration / btScalar(config.piterations);
      for (int stage = 0; stage < config.m_psequence.size(); ++stage) {
        const btSoftBody::psolver_t solver = btSoftBody::getSolver(config.m_psequence[stage]);
        if (config.m_psequence[stage] == btSoftBody::ePSolver::RContacts) {
          measuredContactStage([&] { solver(&body, 1, fraction); });
        } else {
          solver(&body, 1, fraction);
        }
      }
      if (m_holdsLast) measuredContactStage([&] { solveHoldsLast(body); });
    }
    reactToHolds(body);
    const btScalar velocityFactor = body.m_sst.isdt * (1 - config.kDP);
    // This is the last pass over the nodes unless drift iterations or clusters follow, which move
    // them again: the last word's survey of the body runs in it, on nodes already in cache, for
    // the step the last word is about to read (m_step advances after the solve). The whole pass,
    // Bullet's velocities in it, counts as the last word's time.
    const auto start = std::chrono::steady_clock::now();
    SoftBodyCache* surveyed =
        m_hasStepReach && config.diterations == 0 && body.m_clusters.size() == 0 ? &topologyOf(body) : nullptr;
    NodeSurvey survey;
    if (surveyed != nullptr) survey = beginSurvey(*surveyed, m_step + 1);
    // The guard's shares, where nothing after this pass but the last word changes a velocity.
    SoftBodyCache* shared =
        guarded && config.diterations == 0 && body.m_clusters.size() == 0 ? &topologyOf(body) : nullptr;
    if (shared != nullptr) {
      shared->solvedMass = 0;
      shared->motionSolved = true;
    }
    const btScalar longestMoveSquared = longestMove < BT_LARGE_FLOAT ? longestMove * longestMove : BT_LARGE_FLOAT;
    Index shortened = 0;
    Index nonFinite = 0;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      btSoftBody::Node& node = body.m_nodes[i];
      const btVector3 move = node.m_x - node.m_q;
      const btScalar moveSquared = move.length2();
      if (moveSquared > longestMoveSquared && node.m_im > 0) {
        const btVector3 before = node.m_x;
        node.m_x = node.m_q + move * btSqrt(longestMoveSquared / moveSquared);
        detail::checkWrite(before, node.m_x, nonFinite);
        ++shortened;
      }
      node.m_v = (node.m_x - node.m_q) * velocityFactor;
      node.m_f = btVector3(0, 0, 0);
      if (shared != nullptr) shared->solvedMass += keepShares(*shared, i, node.m_v, node.m_im);
      if (surveyed != nullptr) {
        surveyNode(survey, *surveyed, i, node.m_x, node.m_q, m_dynamicToolsActive && !(node.m_im > 0));
      }
    }
    if (shortened > 0 || nonFinite > 0) {
      reportToToolsNear(body, [&](LastWordDiagnostics& lastWord) {
        lastWord.movesShortened += shortened;
        lastWord.nonFiniteWrites += nonFinite;
      });
    }
    if (surveyed != nullptr) {
      const auto passEnd = std::chrono::steady_clock::now();
      finishSurvey(survey, *surveyed, body, Real(btSqrt(longestEdgeSquared)));
      LastWordDiagnostics& lastWord = m_active.front()->state().lastWord;
      lastWord.microseconds +=
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      lastWord.sharedPassMicroseconds += std::chrono::duration<double, std::micro>(passEnd - start).count();
    }
  }
  if (config.diterations > 0) {
    const btScalar driftFactor = config.kVCF * body.m_sst.isdt;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      btSoftBody::Node& node = body.m_nodes[i];
      node.m_q = node.m_x;
    }
    for (int iteration = 0; iteration < config.diterations; ++iteration) {
      for (int stage = 0; stage < config.m_dsequence.size(); ++stage) {
        btSoftBody::getSolver(config.m_dsequence[stage])(&body, 1, 0);
      }
    }
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      btSoftBody::Node& node = body.m_nodes[i];
      node.m_v += (node.m_x - node.m_q) * driftFactor;
    }
  }
  body.dampClusters();
  body.applyClusters(true);
  for (const ReachingHold& hold : m_reachingHolds) body.m_rcontacts[hold.contact].m_cti.m_normal = hold.normal;
}

void SoftBodySolverImpl::solveConstraints(btScalar timeStep) {
  using Clock = std::chrono::steady_clock;
  const auto measureStart = Clock::now();
  measureEnergy(timeStep);
  const auto measureEnd = Clock::now();
  // Before Bullet's solve, which moves no tool: the solve surveys the bodies it solves for them.
  beginLastWord();
  solveSoftBodies();
  ++m_step;
  separateEverything();
  const auto guardStart = Clock::now();
  guardEnergy();
  const auto guardEnd = Clock::now();
  // The guard's time, before and after Bullet's solve, shared among the tools that have it on.
  const auto guarding = std::count_if(m_configuration.tools().begin(), m_configuration.tools().end(),
                                      [](const Tool* tool) { return tool->state().options.energyGuard.enabled; });
  if (guarding > 0) {
    const double share = (std::chrono::duration<double, std::micro>(measureEnd - measureStart).count() +
                          std::chrono::duration<double, std::micro>(guardEnd - guardStart).count()) /
                         double(guarding);
    for (Tool* tool : m_configuration.tools()) {
      if (!tool->state().options.energyGuard.enabled) continue;
      tool->state().lastWord.microseconds += share;
      tool->state().lastWord.energyGuardMicroseconds += share;
    }
  }
  endLastWord();
}

void SoftBodySolverImpl::rememberStarts() {
  m_starts.resize(static_cast<std::size_t>(m_softBodySet.size()));
  const bool anyTool = std::any_of(m_configuration.tools().begin(), m_configuration.tools().end(),
                                   [](const Tool* tool) { return tool->state().options.separation.enabled; });
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    std::vector<btVector3>& starts = m_starts[static_cast<std::size_t>(s)];
    starts.clear();
    const btSoftBody& body = *m_softBodySet[s];
    if (!anyTool || !body.isActive()) continue;
    starts.resize(static_cast<std::size_t>(body.m_nodes.size()));
    for (int i = 0; i < body.m_nodes.size(); ++i) starts[static_cast<std::size_t>(i)] = body.m_nodes[i].m_x;
  }
}

void SoftBodySolverImpl::rememberSpeeds(bool pressureBodiesOnly) {
  m_startFastest.assign(static_cast<std::size_t>(m_softBodySet.size()), 0);
  const bool anyGuard = std::any_of(m_configuration.tools().begin(), m_configuration.tools().end(),
                                    [](const Tool* tool) { return tool->state().options.energyGuard.enabled; });
  if (!anyGuard) return;
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    const btSoftBody& body = *m_softBodySet[s];
    if (pressureBodiesOnly) {
      if (body.m_cfg.kPR == 0 || !body.isActive()) continue;
      // The guard kept the body's speed at the end of the last step (recordPressureSpeeds), which
      // measureEnergy reads before this: no pass over its nodes.
      const SoftBodyCache* speeds = findCache(body);
      if (speeds != nullptr && speeds->speedStep == m_step) continue;
    }
    btScalar fastestSquared = 0;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      if (body.m_nodes[i].m_im > 0) fastestSquared = std::max(fastestSquared, body.m_nodes[i].m_v.length2());
    }
    m_startFastest[static_cast<std::size_t>(s)] = double(btSqrt(fastestSquared));
  }
}

void SoftBodySolverImpl::lastWordAfterTransforms() {
  beginLastWord();
  // Bullet's applyTransforms left each node's m_q at its end; the last word reads the node's
  // start there, as in the classic solver, and the deformable solver finds m_q at the end again.
  // The bodies whose nodes' moves over the step meet the step's reach, each with the guard's
  // speed bound, which the tools' poses set for the whole step.
  m_speedBound.assign(static_cast<std::size_t>(m_softBodySet.size()), kNotReached);
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    btSoftBody& body = *m_softBodySet[s];
    const std::vector<btVector3>& starts = m_starts[static_cast<std::size_t>(s)];
    if (!lastWordReaches(body) || starts.size() != static_cast<std::size_t>(body.m_nodes.size())) continue;
    btVector3 low(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
    btVector3 high = -low;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      const btVector3& start = starts[static_cast<std::size_t>(i)];
      low.setMin(start);
      high.setMax(start);
      low.setMin(body.m_nodes[i].m_x);
      high.setMax(body.m_nodes[i].m_x);
    }
    // A node that is not finite escapes the box: the body is looked at, as the gather must.
    const bool finite = isFinite(toVec3(low)) && isFinite(toVec3(high));
    if (finite && !m_stepReach.overlaps(Aabb{toVec3(low), toVec3(high)})) continue;
    for (int i = 0; i < body.m_nodes.size(); ++i) body.m_nodes[i].m_q = starts[static_cast<std::size_t>(i)];
    const auto b = static_cast<std::size_t>(s);
    m_speedBound[b] = deformableSpeedBound(body, b < m_startFastest.size() ? m_startFastest[b] : 0);
    // The bound before the last word, on the moves Bullet's solve made; after it, on the velocities.
    boundDeformableSpeeds(body, m_speedBound[b], true);
  }
  ++m_step;
  separateEverything();
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    if (m_speedBound[static_cast<std::size_t>(s)] == kNotReached) continue;
    btSoftBody& body = *m_softBodySet[s];
    boundDeformableSpeeds(body, m_speedBound[static_cast<std::size_t>(s)], false);
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      btSoftBody::Node& node = body.m_nodes[i];
      node.m_q = node.m_x;
      node.m_vn = node.m_v;
    }
  }
  endLastWord();
}

void SoftBodySolverImpl::addSolverImpulse(const btCollisionObject& object, const btVector3& impulse,
                                          const btVector3& point, btScalar timeStep) {
  Tool* tool = m_configuration.findTool(object);
  if (tool == nullptr || !(timeStep > 0)) return;
  const Vec3 force = toVec3(impulse) / Real(timeStep);
  if (!isFinite(force) || !isFinite(toVec3(point))) return;
  addToHoldWrench(tool->state(), toVec3(point), force);
}

double SoftBodySolverImpl::deformableSpeedBound(const btSoftBody& body, double startFastest) const {
  // The bound of the energy guard on node speed (EnergyGuardSettings::speedFactor), without the
  // prediction the classic solver gives: speedFactor times the fastest of the guarding tools'
  // corners over the step and restingSpeed, or the body's fastest free node at the start of the
  // step, whichever is faster. Bullet's implicit solve turns the stretch of the last word's moves
  // into speed in the next steps; this keeps it from growing step upon step (generated seed 185
  // in the deformable world: a needle turning 78° a step through a sheet sent nodes to 1.45e6 m/s).
  double toolFastest = 0;
  double speedFactor = 0;
  double restingSpeed = 0;
  for (Tool* tool : m_active) {
    const EnergyGuardSettings& settings = tool->state().options.energyGuard;
    if (!settings.enabled || detail::ignores(body, tool->body())) continue;
    const Pose now = toPose(tool->body().getWorldTransform());
    toolFastest = std::max(toolFastest, fastestCorner(*tool, stepStart(*tool, now), now, Real(body.m_sst.isdt)));
    speedFactor = std::max(speedFactor, double(settings.speedFactor));
    restingSpeed = std::max(restingSpeed, double(settings.restingSpeed));
  }
  if (!(speedFactor > 0)) return -1;
  return std::max(speedFactor * std::max(restingSpeed, toolFastest), startFastest);
}

void SoftBodySolverImpl::boundDeformableSpeeds(btSoftBody& body, double allowed, bool moves) {
  if (!(allowed >= 0)) return;
  const btScalar longest = btScalar(allowed) * body.m_sst.sdt;
  Index slowed = 0;
  Index nonFinite = 0;
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    btSoftBody::Node& node = body.m_nodes[i];
    if (!(node.m_im > 0)) continue;
    if (moves) {
      // m_q holds the node's start here.
      const btVector3 move = node.m_x - node.m_q;
      const btScalar length = move.length();
      if (!(length > longest)) continue;
      const btVector3 before = node.m_x;
      node.m_x = node.m_q + move * (longest / length);
      detail::checkWrite(before, node.m_x, nonFinite);
    } else {
      const double speed = double(node.m_v.length());
      if (!(speed > allowed)) continue;
      const btVector3 before = node.m_v;
      node.m_v *= btScalar(allowed / speed);
      detail::checkWrite(before, node.m_v, nonFinite);
    }
    ++slowed;
  }
  if (slowed == 0 && nonFinite == 0) return;
  for (Tool* tool : m_active) {
    if (!tool->state().options.energyGuard.enabled || detail::ignores(body, tool->body())) continue;
    (moves ? tool->state().lastWord.movesShortened : tool->state().lastWord.nodesSlowed) += slowed;
    tool->state().lastWord.nonFiniteWrites += nonFinite;
  }
}

void SoftBodySolverImpl::beginLastWord() {
  for (Tool* tool : m_configuration.tools()) {
    tool->state().holdWrench = Wrench{};
    tool->state().holdNodesShared = 0;
  }
  // The tools whose last word runs, and where their pieces reach.
  std::vector<Tool*>& tools = m_active;
  tools.clear();
  m_dynamicToolsActive = false;
  for (Tool* tool : m_configuration.tools()) {
    tool->state().lastWord = LastWordDiagnostics{};
    // The pose-matching frames this step's prediction repaired, of the bodies the tool is at.
    for (const auto& pair : tool->state().pairs) {
      const SoftBodyCache* cache = pair->live ? findCache(*pair->softBody) : nullptr;
      if (cache == nullptr || cache->frameRepairStep != m_step) continue;
      ++tool->state().lastWord.poseFramesRepaired;
      tool->state().lastWord.nonFiniteWrites += cache->frameNonFiniteWrites;
    }
    if (tool->state().options.separation.enabled && isFinite(toPose(tool->body().getWorldTransform()))) {
      tools.push_back(tool);
      m_dynamicToolsActive = m_dynamicToolsActive || bool(reactingBody(tool->state()));
    }
  }
  m_stepReach = Aabb{};
  for (Tool* tool : tools) {
    const Pose now = toPose(tool->body().getWorldTransform());
    const Pose before = stepStart(*tool, now);
    for (Index p = 0; p < tool->pieceCount(); ++p) {
      const PieceMotion motion(before, now, tool->state().options.separation.maxTurnPerSample, tool->pieceTransform(p));
      m_stepReach.include(sweptBounds(tool->piece(p).bounds, motion).expanded(tool->state().options.separation.clearance));
    }
  }
  m_hasStepReach = !tools.empty() && isFinite(m_stepReach.min) && isFinite(m_stepReach.max);
}

void SoftBodySolverImpl::separateEverything() {
  // One piece's moves can push soft features into another (two jaws, two tools): the pieces take
  // turns until a pass moves nothing, or a pass had a single piece near soft features. Pieces
  // still pushing faces into each other after the last pass leave them to the last resort, which
  // carries what meets a piece with it from the start of the step, where it met none.
  // A carry of crossed faces moves their nodes with the piece, as far as the piece went: the faces
  // they share with nodes left behind are looked at in another pass (generated seed 979).
  for (int pass = 0; pass < kMostPasses; ++pass) {
    m_piecesNear = 0;
    m_carried = false;
    bool moved = false;
    for (Tool* tool : m_active) {
      moved = separate(*tool, Stage::Rounds) || moved;
    }
    if (!moved || (m_piecesNear <= 1 && !m_carried)) break;
    if (pass + 1 == kMostPasses) {
      for (Tool* tool : m_active) separate(*tool, Stage::LastResort);
      for (Tool* tool : m_active) separate(*tool, Stage::NodesLast);
    }
  }
  m_hasStepReach = false;
}

void SoftBodySolverImpl::endLastWord() {
  for (Tool* tool : m_active) {
    tool->state().separatedPose = toPose(tool->body().getWorldTransform());
    tool->state().hasSeparatedPose = true;
    tool->state().separationJump = false;
    tool->state().lastWord.ran = true;
  }
}

Pose SoftBodySolverImpl::stepStart(const Tool& tool, const Pose& now) {
  return tool.state().hasSeparatedPose && !tool.state().separationJump ? tool.state().separatedPose : now;
}

void SoftBodySolverImpl::measureEnergy(btScalar timeStep) {
  if (m_energy.size() < static_cast<std::size_t>(m_softBodySet.size())) {
    m_energy.resize(static_cast<std::size_t>(m_softBodySet.size()));
  }
  const Real inverseStep = 1 / Real(timeStep);
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    btSoftBody& softBody = *m_softBodySet[s];
    BodyEnergy& energy = m_energy[static_cast<std::size_t>(s)];
    energy = BodyEnergy{};
    // Guarded when a tool's response moved a node of it in the collision pass or the holds of a
    // tool that does not give way hold one in the solve: such a hold alone, in a step the response
    // moved nothing, moves its node to the tool's plane as hard as a correction (a tetrahedral box
    // in kinematic jaws went from 8 to 105 m/s in three such steps, generated seed 35634). A
    // dynamic tool gives way: it takes its holds' push back (reactToHolds, as an inelastic
    // exchange) or its force model carries it, and slowing its held nodes broke that exchange (a
    // force-carried plate bounced at 0.46 m/s in Bullet's float64 build,
    // ForceScene.DynamicToolIsCarriedByTheForce; the gripper's cube weighed 13.5 % heavy there).
    bool guarded = false;
    for (Tool* tool : m_configuration.tools()) {
      const EnergyGuardSettings& settings = tool->state().options.energyGuard;
      if (!settings.enabled) continue;
      // The tool's motion over the step, as the last word reads it: a point of the tool at x moved
      // from before·now⁻¹·x.
      const Pose now = toPose(tool->body().getWorldTransform());
      const Pose before = stepStart(*tool, now);
      bool guarding = false;
      double corner = 0;
      const bool guardsHolds = !tool->state().dynamic();  // its holds alone make the guard act
      for (const auto& pair : tool->state().pairs) {
        if (pair->softBody != &softBody || !pair->live) continue;
        if (!pair->response.corrections.empty() || pair->holdCount > 0) ++energy.piecesHolding;
        bool holding = false;
        for (int k = 0; k < pair->holdCount && guardsHolds && !holding; ++k) {
          holding = heldNode(softBody, *pair, k) != nullptr;
        }
        if (pair->response.corrections.empty() && !holding) continue;
        if (!guarding) {
          corner = fastestCorner(*tool, before, now, inverseStep);
          energy.toolFastest = std::max(energy.toolFastest, corner);
        }
        guarding = true;
        guarded = true;
        energy.boundForcesNextStep = energy.boundForcesNextStep || settings.boundForcesNextStep;
        energy.speedFactor = std::max(energy.speedFactor, double(settings.speedFactor));
        energy.energySlack = std::max(energy.energySlack, double(settings.energySlack));
        energy.restingSpeed = std::max(energy.restingSpeed, double(settings.restingSpeed));
        energy.lastWordFollows = energy.lastWordFollows || tool->state().options.separation.enabled;
        // Each node the tool moves, by the response or by a hold, may leave at the tool's speed
        // there (a node both moved and held counts twice: the bound stays an upper one).
        const auto allow = [&](const btSoftBody::Node* node) {
          if (node == nullptr) return;
          const Vec3 at = toVec3(node->m_x);
          // No point of a convex piece moves faster than its fastest corner (the chord's velocity
          // is affine in the point): a node the response moved but left away from the piece, where
          // the tool's turn would sweep faster, is given the corner's speed at most.
          const double toolSpeed =
              std::min(double(length((at - before.apply(now.applyInverse(at))) * inverseStep)), corner);
          if (!std::isfinite(toolSpeed)) return;
          energy.allowance += 0.5 * toolSpeed * toolSpeed / double(node->m_im);
          energy.toolAtMovedNodes = std::max(energy.toolAtMovedNodes, toolSpeed);
        };
        for (const NodeCorrection& correction : pair->response.corrections) {
          allow(movedNode(softBody, *pair, correction));
        }
        for (int k = 0; k < pair->holdCount && guardsHolds; ++k) allow(heldNode(softBody, *pair, k));
      }
    }
    if (!guarded) continue;
    // Each node's motion as Bullet set it up for the solve, (x - q)/dt: its forces, gravity and
    // pose matching; the fastest node is read from the velocity Bullet predicted, in the same pass.
    // A square root for the fastest only: the root of the largest square is the largest root.
    const btScalar inverseStepBt = softBody.m_sst.isdt;
    btScalar fastestSquared = 0;
    BodyMotion motion = motionOf(softBody, [&](const btSoftBody::Node& node) {
      fastestSquared = std::max(fastestSquared, node.m_v.length2());
      return (node.m_x - node.m_q) * inverseStepBt;
    });
    energy.predictedFastest = double(btSqrt(fastestSquared));
    // A pressure body's own speed is what it kept through the last steps, not its prediction: the
    // fastest node the guard left in the last step, or speedFactor times the fastest of the latest
    // step the guard did not act in; with no such step, speedFactor times its fastest node at the
    // start of this one. A plate set down beside a light pressure ellipsoid, whose nodes Bullet
    // predicted at up to 205 m/s, left one at 55 m/s in its first step, where the body had kept
    // 6.6 m/s (generated seed 6261 with the faces scanned).
    const SoftBodyCache* speeds = softBody.m_cfg.kPR != 0 ? findCache(softBody) : nullptr;
    if (speeds != nullptr && speeds->speedStep == m_step) {
      energy.predictedFastest = std::min(energy.predictedFastest,
                                         std::max(energy.speedFactor * speeds->ownFastest, speeds->endFastest));
    } else if (softBody.m_cfg.kPR != 0 && static_cast<std::size_t>(s) < m_startFastest.size()) {
      energy.predictedFastest =
          std::min(energy.predictedFastest, energy.speedFactor * m_startFastest[static_cast<std::size_t>(s)]);
    }
    // The response's moves are not the body's own motion: what they add is taken back out.
    for (Tool* tool : m_configuration.tools()) {
      if (!tool->state().options.energyGuard.enabled) continue;
      for (const auto& pair : tool->state().pairs) {
        if (pair->softBody != &softBody || !pair->live) continue;
        for (const NodeCorrection& correction : pair->response.corrections) {
          const btSoftBody::Node* node = movedNode(softBody, *pair, correction);
          if (node == nullptr || !isFinite(correction.displacement)) continue;
          const double m = 1 / double(node->m_im);
          const btVector3 moved = (node->m_x - node->m_q) * inverseStepBt;
          const btVector3 own = moved - toBt(correction.displacement) * inverseStepBt;
          motion.kinetic += 0.5 * m * double(own.length2() - moved.length2());
          motion.momentum += (own - moved) * btScalar(m);
        }
      }
    }
    const double internal =
        motion.mass > 0 ? motion.kinetic - 0.5 * double(motion.momentum.length2()) / motion.mass : 0;
    if (std::isfinite(internal) && std::isfinite(energy.predictedFastest)) energy.predicted = std::max(internal, 0.0);
  }
}

void SoftBodySolverImpl::beginToolSteps(btScalar timeStep) {
  for (Tool* tool : m_configuration.tools()) {
    tool->state().applied = detail::AppliedImpulse{};
    tool->state().stepLength = timeStep;
    tool->state().deformableNodeContacts = 0;
  }
}

void SoftBodySolverImpl::predictMotion(btScalar timeStep) {
  beginToolSteps(timeStep);
  rememberSpeeds(true);
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    btSoftBody& softBody = *m_softBodySet[s];
    if (!softBody.isActive()) continue;
    SoftBodyCache* cache = findCache(softBody);
    if (cache == nullptr || cache->boundStep != m_step || softBody.m_worldInfo == nullptr) {
      softBody.predictMotion(timeStep);
      if (cache != nullptr) keepPoseFrame(softBody, *cache);
      continue;
    }
    // Bullet's own bound on a node's change of velocity from its forces in one step
    // (btSoftBodyWorldInfo::m_maxDisplacement over the step, per axis), lowered for this body's
    // prediction only: the world info is shared with every other soft body.
    btScalar& maxDisplacement = softBody.m_worldInfo->m_maxDisplacement;
    const btScalar userMaxDisplacement = maxDisplacement;
    const btScalar dt = timeStep * softBody.m_cfg.timescale;
    const btScalar limited = btScalar(cache->nextForceBound) * dt;
    maxDisplacement = btMin(userMaxDisplacement, limited);
    softBody.predictMotion(timeStep);
    maxDisplacement = userMaxDisplacement;
    keepPoseFrame(softBody, *cache);
    if (!(limited < userMaxDisplacement)) continue;
    // The forces that needed the bound may act again in the next step (the pressure of a body
    // squeezed flat): it stays while a node is predicted as fast as it allows.
    const btScalar fastestSquared = btScalar(cache->nextForceBound * cache->nextForceBound);
    for (int i = 0; i < softBody.m_nodes.size(); ++i) {
      if (softBody.m_nodes[i].m_v.length2() >= fastestSquared) {
        cache->boundStep = m_step + 1;
        break;
      }
    }
  }
}

void SoftBodySolverImpl::keepPoseFrame(btSoftBody& softBody, SoftBodyCache& cache) {
  // Bullet's pose matching (btSoftBody::predictMotion: updatePose, then every free node pulled kMT
  // of the way to its place in the body's frame) takes the frame's rotation from
  // btPolarDecomposition, which returns a matrix that is no rotation when its iteration does not
  // converge, on a nearly singular Apq = Σ w·(x − com) ⊗ rest offset. A flat body's rest offsets
  // lie in a plane, so its Apq is singular but for Bullet's epsilon, and folded it may defeat the
  // iteration: a free cloth folded over jaws (generated seed 1766 with --bullet-kinds) got a
  // frame with entries of 5,000 (determinant 1e11), and the match sent nodes 390 m in one step.
  // Where the frame is not a rotation, the match is made again from the prediction (m_q + m_v·dt,
  // as Bullet computed it) with the rotation nearest Apq that the iteration of Müller et al. 2016
  // ("A robust method to extract the rotational part of deformations") reaches from the last good
  // frame: a rotation at every iteration, however singular Apq is. A reflection (determinant −1)
  // is left as Bullet found it: a flat body's reflection through its own plane is the same shape.
  btSoftBody::Pose& pose = softBody.m_pose;
  if (!pose.m_bframe || !(softBody.m_cfg.kMT > 0) || pose.m_pos.size() != softBody.m_nodes.size() ||
      pose.m_wgh.size() != softBody.m_nodes.size()) {
    return;
  }
  const btMatrix3x3& frame = pose.m_rot;
  const btMatrix3x3 square = frame * frame.transpose();
  bool orthonormal = true;
  for (int i = 0; i < 3 && orthonormal; ++i) {
    for (int j = 0; j < 3 && orthonormal; ++j) {
      orthonormal = btFabs(square[i][j] - btScalar(i == j ? 1 : 0)) < kFrameTolerance;
    }
  }
  if (orthonormal) {
    // The start of the next repair's iteration, a rotation: a reflection R gives −R.
    cache.poseFrame = frame.determinant() > 0 ? frame : frame.scaled(btVector3(-1, -1, -1));
    return;
  }
  const btScalar dt = softBody.m_sst.sdt;
  btMatrix3x3 apq(0, 0, 0, 0, 0, 0, 0, 0, 0);
  for (int i = 0; i < softBody.m_nodes.size(); ++i) {
    const btSoftBody::Node& node = softBody.m_nodes[i];
    const btVector3 a = pose.m_wgh[i] * (node.m_q + node.m_v * dt - pose.m_com);
    const btVector3& b = pose.m_pos[i];
    apq[0] += a.x() * b;
    apq[1] += a.y() * b;
    apq[2] += a.z() * b;
  }
  btQuaternion turn;
  cache.poseFrame.getRotation(turn);
  turn.normalize();
  for (int iteration = 0; iteration < kFrameIterations; ++iteration) {
    const btMatrix3x3 r(turn);
    btVector3 torque(0, 0, 0);
    btScalar alignment = 0;
    for (int c = 0; c < 3; ++c) {
      torque += r.getColumn(c).cross(apq.getColumn(c));
      alignment += r.getColumn(c).dot(apq.getColumn(c));
    }
    const btVector3 omega = torque / (btFabs(alignment) + btScalar(1e-9));
    const btScalar angle = omega.length();
    if (!(angle > btScalar(1e-9))) break;
    turn = (btQuaternion(omega / angle, angle) * turn).normalized();
  }
  const btMatrix3x3 repaired(turn);
  Index nonFinite = 0;
  for (int i = 0; i < softBody.m_nodes.size(); ++i) {
    btSoftBody::Node& node = softBody.m_nodes[i];
    if (!(node.m_im > 0)) continue;
    const btVector3 before = node.m_x;
    const btVector3 predicted = node.m_q + node.m_v * dt;
    node.m_x = predicted + (repaired * pose.m_pos[i] + pose.m_com - predicted) * softBody.m_cfg.kMT;
    detail::checkWrite(before, node.m_x, nonFinite);
  }
  pose.m_rot = repaired;
  cache.poseFrame = repaired;
  cache.frameRepairStep = m_step;
  cache.frameNonFiniteWrites = nonFinite;
}

void SoftBodySolverImpl::recordPressureSpeeds(btSoftBody& softBody, bool guarded, double fastest) {
  SoftBodyCache* cache = findCache(softBody);
  if (cache == nullptr || softBody.m_cfg.kPR == 0) return;
  cache->endFastest = fastest;
  if (!guarded) cache->ownFastest = fastest;
  cache->speedStep = m_step;
}

void SoftBodySolverImpl::guardEnergy() {
  for (int s = 0; s < m_softBodySet.size(); ++s) {
    const BodyEnergy& energy = m_energy[static_cast<std::size_t>(s)];
    btSoftBody& softBody = *m_softBodySet[s];
    if (energy.predicted < 0) {
      // Unguarded, a pressure body near a guarding tool keeps its own speed for the steps the
      // guard acts in.
      if (softBody.m_cfg.kPR != 0 && softBody.isActive() && guardingToolNear(softBody)) {
        btScalar fastestSquared = 0;
        for (int i = 0; i < softBody.m_nodes.size(); ++i) {
          fastestSquared = std::max(fastestSquared, softBody.m_nodes[i].m_v.length2());
        }
        recordPressureSpeeds(softBody, false, double(btSqrt(fastestSquared)));
      }
      continue;
    }
    // The energy about the centre of mass, as the solve left it: the body's motion as a whole is
    // the tool's push or its fall, which the bound must not damp.
    btScalar fastestSquared = 0;
    const BodyMotion motion = motionAfterLastWord(softBody, fastestSquared);
    const double fastest = double(btSqrt(fastestSquared));
    if (!(motion.mass > 0)) continue;
    const btVector3 mean = motion.momentum / btScalar(motion.mass);
    const double internal = motion.kinetic - 0.5 * motion.mass * double(mean.length2());
    const double bound = std::max((1 + energy.energySlack) * energy.predicted + energy.allowance,
                                  0.5 * motion.mass * energy.restingSpeed * energy.restingSpeed);
    const btScalar scale =
        internal > bound && std::isfinite(internal) ? btScalar(std::sqrt(bound / internal)) : btScalar(1);
    const double removed = scale < 1 ? internal - bound : 0;
    // No node faster than the bound: the tool gives a node its own speed at most, a stiff link a
    // few times that within a step. Then the energy's scale, about the mean.
    const double fastestAllowed = SoftBodySolverImpl::fastestAllowed(energy);
    SoftBodyCache* cache = nullptr;
    const auto boundNextStep = [&](double fastestLeft) {
      if (!energy.boundForcesNextStep) return;
      if (cache == nullptr) cache = &cacheOf(softBody);
      cache->boundStep = m_step;
      // In a grasp, the holds on both sides take back what the body's pressure kicks (the clamp's
      // vessel); against one piece the body bulges away with the kick (generated seed 748).
      double acrossBody = 0;
      if (energy.piecesHolding > 1) {
        btVector3 low(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
        btVector3 high = -low;
        for (int i = 0; i < softBody.m_nodes.size(); ++i) {
          const btSoftBody::Node& node = softBody.m_nodes[i];
          if (!(node.m_im > 0)) continue;
          low.setMin(node.m_x);
          high.setMax(node.m_x);
        }
        acrossBody = double((high - low).length() * softBody.m_sst.isdt);
      }
      cache->nextForceBound =
          std::max(energy.speedFactor * std::max({energy.restingSpeed, energy.toolFastest, fastestLeft}), acrossBody);
    };
    boundNextStep(fastest);
    if (!(scale < 1) && !(fastest > fastestAllowed)) {  // within both bounds: no second pass
      recordPressureSpeeds(softBody, true, fastest);
      continue;
    }
    Index slowed = 0;
    Index nonFinite = 0;
    btScalar leftSquared = 0;
    for (int i = 0; i < softBody.m_nodes.size(); ++i) {
      btSoftBody::Node& node = softBody.m_nodes[i];
      if (!(node.m_im > 0)) continue;
      const btVector3 before = node.m_v;
      const double speed = double(node.m_v.length());
      if (speed > fastestAllowed) {
        node.m_v *= btScalar(fastestAllowed / speed);
        ++slowed;
      }
      if (scale < 1) node.m_v = mean + (node.m_v - mean) * scale;
      detail::checkWrite(before, node.m_v, nonFinite);
      leftSquared = std::max(leftSquared, node.m_v.length2());
    }
    boundNextStep(double(btSqrt(leftSquared)));
    recordPressureSpeeds(softBody, true, double(btSqrt(leftSquared)));
    if (slowed == 0 && removed == 0 && nonFinite == 0) continue;
    reportToToolsNear(softBody, [&](LastWordDiagnostics& lastWord) {
      lastWord.nodesSlowed += slowed;
      lastWord.energyRemoved += removed;
      lastWord.nonFiniteWrites += nonFinite;
    });
  }
}

BodyMotion SoftBodySolverImpl::motionAfterLastWord(const btSoftBody& softBody, btScalar& fastestSquared) {
  fastestSquared = 0;
  SoftBodyCache* cache = findCache(softBody);
  if (cache == nullptr || !cache->motionSolved) {
    return motionOf(softBody, [&](const btSoftBody::Node& node) {
      fastestSquared = std::max(fastestSquared, node.m_v.length2());
      return node.m_v;
    });
  }
  for (const Index changed : cache->changed) {
    const btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(changed)];
    keepShares(*cache, static_cast<int>(changed), node.m_v, node.m_im);
    cache->isChanged[changed] = 0;
  }
  cache->changed.clear();
  cache->motionSolved = false;
  // Adding a pinned node's zero shares leaves each sum as it was, to the bit.
  BodyMotion motion;
  motion.mass = cache->solvedMass;
  const auto nodeCount = static_cast<std::size_t>(softBody.m_nodes.size());
  for (std::size_t i = 0; i < nodeCount; ++i) {
    motion.kinetic += cache->kineticShare[i];
    motion.momentum += cache->momentumShare[i];
    fastestSquared = std::max(fastestSquared, cache->speedSquared[i]);
  }
  return motion;
}

double SoftBodySolverImpl::keepShares(SoftBodyCache& cache, int i, const btVector3& v, btScalar im) {
  const auto n = static_cast<std::size_t>(i);
  if (!(im > 0)) {
    cache.kineticShare[n] = 0;
    cache.momentumShare[n] = btVector3(0, 0, 0);
    cache.speedSquared[n] = 0;
    return 0;
  }
  const double m = 1 / double(im);
  cache.kineticShare[n] = kineticShareOf(v, m);
  cache.momentumShare[n] = momentumShareOf(v, m);
  cache.speedSquared[n] = v.length2();
  return m;
}

bool SoftBodySolverImpl::separate(Tool& tool, Stage stage) {
  const auto start = std::chrono::steady_clock::now();
  const SeparationSettings& settings = tool.state().options.separation;
  const Pose now = toPose(tool.body().getWorldTransform());
  const Pose before = stepStart(tool, now);
  // What is left is what the latest pass left; the moves add up over the passes.
  SeparationCounts& counts = tool.state().lastWord.counts;
  counts.nodesInside = 0;
  counts.facesPierced = 0;
  bool moved = false;
  for (Index p = 0; p < tool.pieceCount(); ++p) {
    const PieceMotion motion(before, now, settings.maxTurnPerSample, tool.pieceTransform(p));
    findNearPieces(tool, p, motion);
    for (int s = 0; s < m_softBodySet.size(); ++s) {
      btSoftBody& softBody = *m_softBodySet[s];
      if (detail::ignores(softBody, tool.body()) || !actsOn(softBody)) continue;
      // A deformable body the step's reach misses keeps its end in m_q, not its start.
      if (m_deformable && m_speedBound[static_cast<std::size_t>(s)] == kNotReached) continue;
      const SeparationCounts piece = separatePiece(tool, tool.piece(p), motion, softBody, stage, m_nearPieces);
      moved = moved || piece.nodesMoved > 0 || piece.facesMoved > 0;
      counts.accumulate(piece);
    }
  }
  tool.state().lastWord.microseconds +=
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  return moved;
}

SoftBodySolverImpl::SoftBodyCache* SoftBodySolverImpl::findCache(const btSoftBody& softBody) {
  for (SoftBodyCache& cache : m_caches) {
    if (cache.softBody == &softBody) return &cache;
  }
  return nullptr;
}

SoftBodySolverImpl::SoftBodyCache& SoftBodySolverImpl::cacheOf(const btSoftBody& softBody) {
  SoftBodyCache& cache = topologyOf(softBody);
  if (cache.stepSeen != m_step) {
    NodeSurvey survey = beginSurvey(cache, m_step);
    for (int i = 0; i < softBody.m_nodes.size(); ++i) {
      const btSoftBody::Node& node = softBody.m_nodes[i];
      surveyNode(survey, cache, i, node.m_x, node.m_q, m_dynamicToolsActive && !(node.m_im > 0));
    }
    finishSurvey(survey, cache, softBody);
  }
  return cache;
}

SoftBodySolverImpl::SoftBodyCache& SoftBodySolverImpl::topologyOf(const btSoftBody& softBody) {
  SoftBodyCache* found = findCache(softBody);
  if (found == nullptr) {
    m_caches.emplace_back();
    found = &m_caches.back();
    found->softBody = &softBody;
  }
  SoftBodyCache& cache = *found;
  const auto nodeCount = static_cast<Index>(softBody.m_nodes.size());
  const auto faceCount = static_cast<Index>(softBody.m_faces.size());
  if (m_faceInPatch.size() < faceCount) m_faceInPatch.resize(faceCount, 0);
  if (m_vertexOfNode.size() < nodeCount) m_vertexOfNode.resize(nodeCount, kInvalidIndex);
  if (m_isNearNode.size() < nodeCount) m_isNearNode.resize(nodeCount, 0);
  const void* nodes = nodeCount > 0 ? static_cast<const void*>(&softBody.m_nodes[0]) : nullptr;
  const void* faceArray = faceCount > 0 ? static_cast<const void*>(&softBody.m_faces[0]) : nullptr;
  const auto linkCount = static_cast<Index>(softBody.m_links.size());
  const void* linkArray = linkCount > 0 ? static_cast<const void*>(&softBody.m_links[0]) : nullptr;
  if (cache.nodeCount == nodeCount && cache.faceCount == faceCount && cache.nodes == nodes &&
      cache.faceArray == faceArray && cache.linkCount == linkCount && cache.linkArray == linkArray) {
    return cache;
  }
  cache.nodes = nodes;
  cache.faceArray = faceArray;
  cache.linkCount = linkCount;
  cache.linkArray = linkArray;
  // Built when the body's topology is new to the solver or has changed (refine, cut): never in
  // a step that only moves nodes.
  cache.nodeCount = nodeCount;
  cache.faceCount = faceCount;
  cache.measuredReach = -1;
  cache.begin.assign(nodeCount + 1, 0);
  const btSoftBody::Node* first = nodeCount > 0 ? &softBody.m_nodes[0] : nullptr;
  for (Index f = 0; f < faceCount; ++f) {
    for (const btSoftBody::Node* node : softBody.m_faces[static_cast<int>(f)].m_n) {
      ++cache.begin[static_cast<Index>(node - first) + 1];
    }
  }
  for (Index n = 0; n < nodeCount; ++n) cache.begin[n + 1] += cache.begin[n];
  const std::vector<std::pair<Index, Index>> edges = sortedFaceEdges(softBody);
  cache.closed = surfaceIsClosed(edges);
  cache.edgesAreLinks = edgesAreLinks(softBody, edges);
  cache.faces.resize(cache.begin[nodeCount]);
  cache.faceNodes.resize(faceCount);
  std::vector<Index> filled(cache.begin.begin(), cache.begin.end() - 1);
  for (Index f = 0; f < faceCount; ++f) {
    const btSoftBody::Face& face = softBody.m_faces[static_cast<int>(f)];
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<Index>(face.m_n[k] - first);
      cache.faceNodes[f][static_cast<std::size_t>(k)] = node;
      cache.faces[filled[node]++] = f;
    }
  }
  cache.isCandidate.assign(nodeCount, 0);
  cache.kineticShare.assign(nodeCount, 0);
  cache.momentumShare.assign(nodeCount, btVector3(0, 0, 0));
  cache.speedSquared.assign(nodeCount, 0);
  cache.isChanged.assign(nodeCount, 0);
  cache.changed.clear();
  cache.motionSolved = false;
  cache.candidates.clear();
  return cache;
}

// One pass over the nodes serves the face reach, the body's box and the gathers' candidates: the
// gathers of the step's pieces and passes then skip a body their reach misses, and read only the
// candidates of one they meet.
SoftBodySolverImpl::NodeSurvey SoftBodySolverImpl::beginSurvey(SoftBodyCache& cache, int step) {
  // The bound grows with each step's motion; after a step it did not see, it is measured anew.
  if (cache.stepSeen != step - 1) cache.measuredReach = -1;
  cache.stepSeen = step;
  cache.pinned.clear();
  // The last word's moves in the step before stretched faces too, after that step's survey: a
  // body its moves had torn into faces a metre long kept a reach that missed them, and the needle
  // was left across them (generated seed 16703).
  cache.faceReach += cache.lastWordReach;
  cache.lastWordReach = 0;
  cache.candidatesHold = false;
  for (const Index id : cache.candidates) cache.isCandidate[id] = 0;
  cache.candidates.clear();
  cache.candidatesSorted = true;
  NodeSurvey survey;
  cache.candidateReach = kReachGrowth * cache.measuredReach + Real(1e-9);
  survey.collect = m_hasStepReach && cache.measuredReach >= 0;
  // The box in Bullet's scalar, rounded outward: a node it takes and the gather's own test does
  // not is only looked at again.
  const Aabb wanted = m_stepReach.expanded(survey.collect ? cache.candidateReach : 0);
  for (int axis = 0; axis < 3; ++axis) {
    survey.wantedLow[axis] = roundedDown(wanted.min[axis]);
    survey.wantedHigh[axis] = roundedUp(wanted.max[axis]);
  }
  return survey;
}

inline void SoftBodySolverImpl::surveyNode(NodeSurvey& survey, SoftBodyCache& cache, int i, const btVector3& x,
                                      const btVector3& q, bool pinned) {
  if (pinned) cache.pinned.push_back(static_cast<Index>(i));
  // In Bullet's scalar, without branches: this runs for every node of the body each step.
  const btVector3 move = x - q;
  const btScalar moved = move.dot(move);
  survey.farthest = btMax(survey.farthest, moved);  // NaN propagates: the reach is then measured anew
  survey.finite = survey.finite && moved <= std::numeric_limits<btScalar>::max();  // false for NaN
  bool wanted = survey.collect;
  for (int axis = 0; axis < 3; ++axis) {
    const btScalar low = std::min(x[axis], q[axis]);
    const btScalar high = std::max(x[axis], q[axis]);
    survey.lowest[axis] = std::min(survey.lowest[axis], low);
    survey.highest[axis] = std::max(survey.highest[axis], high);
    wanted = wanted && high >= survey.wantedLow[axis] && low <= survey.wantedHigh[axis];
  }
  if (wanted) {
    cache.candidates.push_back(static_cast<Index>(i));
    cache.isCandidate[static_cast<Index>(i)] = 1;
  }
}

void SoftBodySolverImpl::finishSurvey(const NodeSurvey& survey, SoftBodyCache& cache, const btSoftBody& softBody,
                                      Real longestStartEdge) {
  // A node that is not finite escapes the box; the gather then looks at every node, as it must.
  cache.boundsHold = survey.finite;
  cache.bounds = Aabb{toVec3(survey.lowest), toVec3(survey.highest)};
  if (cache.edgesAreLinks && longestStartEdge >= 0) {
    // Two of a face's corners, at the step's start or end, lie no farther apart than its longest
    // edge at the start plus both corners' moves, and so does its box along each axis, which is
    // what the gathers grow their boxes by: a bound each step, with no pass over the faces (a
    // measure over 65,536 faces took as long as the rest of the last word). Rounded up for the
    // lengths Bullet rounded in its scalar.
    const Real reach = (longestStartEdge + 2 * Real(btSqrt(survey.farthest))) *
                       (1 + 16 * Real(std::numeric_limits<btScalar>::epsilon()));
    if (std::isfinite(reach)) {
      cache.candidatesHold =
          survey.collect && survey.finite && cache.measuredReach >= 0 && reach <= cache.candidateReach;
      cache.measuredReach = reach;
      cache.faceReach = reach;
      return;
    }
  }
  if (cache.measuredReach >= 0) {
    cache.faceReach += 2 * Real(btSqrt(survey.farthest));
    cache.candidatesHold = survey.collect && survey.finite;
    if (cache.faceReach <= cache.candidateReach) return;
  }
  Real reach = 0;
  for (const std::array<Index, 3>& corners : cache.faceNodes) {
    btVector3 low = softBody.m_nodes[static_cast<int>(corners[0])].m_x;
    btVector3 high = low;
    for (const Index n : corners) {
      const btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(n)];
      low.setMin(node.m_x);
      low.setMin(node.m_q);
      high.setMax(node.m_x);
      high.setMax(node.m_q);
    }
    reach = std::max(reach, Real((high - low).length()));
  }
  cache.measuredReach = reach;
  cache.faceReach = reach;
  cache.candidatesHold = cache.candidatesHold && reach <= cache.candidateReach;
}

void SoftBodySolverImpl::stopAtPinnedNodes(detail::DynamicBody& tool, const ToolModel& piece, const Pose& pieceEnd,
                                       Real inverseStep, const SoftBodyCache& cache, const btSoftBody& softBody,
                                       Index& nonFiniteWrites) {
  const detail::BodyVelocities before(tool);
  const auto forEachPinned = [&](const auto& visit) {
    for (const Index id : cache.pinned) {
      if (id < static_cast<Index>(softBody.m_nodes.size())) {
        visit(piece, pieceEnd, toVec3(softBody.m_nodes[static_cast<int>(id)].m_x));
      }
    }
  };
  detail::stopShortOfPinnedNodes(tool, forEachPinned, inverseStep, false);
  before.check(nonFiniteWrites);
}

void SoftBodySolverImpl::findBackings(const btSoftBody& softBody) {
  if (m_backingOfNode.size() < static_cast<std::size_t>(softBody.m_nodes.size())) {
    m_backingOfNode.resize(static_cast<std::size_t>(softBody.m_nodes.size()), -1);
  }
  for (int c = 0; c < softBody.m_rcontacts.size(); ++c) {
    const btSoftBody::RContact& contact = softBody.m_rcontacts[c];
    const btCollisionObject* body = contact.m_cti.m_colObj;
    // ThinTool's own holds aim at shapeless bodies of their own; only Bullet's contacts back a node.
    if (body == nullptr || body->getCollisionShape() == nullptr || !body->isStaticOrKinematicObject()) continue;
    m_backingOfNode[static_cast<Index>(contact.m_node - &softBody.m_nodes[0])] = c;
  }
}

// The pieces of any tool, other than piece p of tool, that end the step within a piece's width of
// where piece p swept: near enough for the two to hold a soft face between them. One whose tool's
// pose is not finite counts as near, its place unknown.
void SoftBodySolverImpl::findNearPieces(const Tool& tool, Index p, const PieceMotion& motion) {
  m_nearPieces.clear();
  const ToolModel& piece = tool.piece(p);
  const Aabb reach = sweptBounds(piece.bounds, motion).expanded(length(piece.bounds.extent()));
  for (const Tool* other : m_configuration.tools()) {
    const Pose pose = toPose(other->body().getWorldTransform());
    for (Index q = 0; q < other->pieceCount(); ++q) {
      if (other == &tool && q == p) continue;
      const Pose end = pose * other->pieceTransform(q);
      if (!isFinite(pose) || reach.overlaps(transformedBounds(other->piece(q).bounds, end))) {
        m_nearPieces.push_back({&other->piece(q), end});
      }
    }
  }
}

Index SoftBodySolverImpl::patchVertexOf(const btSoftBody& softBody, const SoftBodyCache& cache, Index node) {
  Index& vertex = m_vertexOfNode[node];
  if (vertex == kInvalidIndex) {
    const btSoftBody::Node& soft = softBody.m_nodes[static_cast<int>(node)];
    const bool enclosed = cache.begin[node] == cache.begin[node + 1];  // on no face
    vertex = m_patch.addVertex(node, toVec3(soft.m_q), toVec3(soft.m_x), Real(soft.m_im), enclosed);
  }
  return vertex;
}

void SoftBodySolverImpl::addPatchFace(const btSoftBody& softBody, const SoftBodyCache& cache, Index f) {
  if (m_faceInPatch[f] != 0) return;
  m_faceInPatch[f] = 1;
  m_patchFaces.push_back(f);
  const std::array<Index, 3>& corners = cache.faceNodes[f];
  m_patch.faces.push_back(
      {patchVertexOf(softBody, cache, corners[0]), patchVertexOf(softBody, cache, corners[1]),
       patchVertexOf(softBody, cache, corners[2])});
}

// A move can carry a node's other faces into the tool, faces the gather had no reason to take:
// those of every moved node join the patch, and the stage runs again, until none is missing.
SeparationCounts SoftBodySolverImpl::separateGrowingPatch(Tool& tool, const ToolModel& piece, const PieceMotion& motion,
                                                     const btSoftBody& softBody, const SoftBodyCache& cache,
                                                     Stage stage, const std::vector<NearPiece>& near) {
  SeparationCounts counts;
  for (int extension = 0;; ++extension) {
    const SeparationSettings& settings = tool.state().options.separation;
    const SeparationCounts run =
        stage == Stage::LastResort  ? carryMeetingFaces(piece, motion, settings, m_patch)
        : stage == Stage::NodesLast ? keepNodesOutside(piece, motion, settings, m_patch)
                                    : separateFromPiece(piece, motion, settings, m_patch, near);
    counts.nodesMoved += run.nodesMoved;
    counts.facesMoved += run.facesMoved;
    counts.nodesInside = run.nodesInside;
    counts.facesPierced = run.facesPierced;
    counts.rounds = std::max(counts.rounds, run.rounds);
    counts.arcSpared = std::max(counts.arcSpared, run.arcSpared);
    if (extension == kMostExtensions) break;
    const std::size_t facesBefore = m_patchFaces.size();
    const Index vertices = m_patch.vertexCount();
    for (Index v = 0; v < vertices; ++v) {
      if (m_patch.moved[v] == 0) continue;
      const Index node = m_patch.nodeIds[v];
      for (Index k = cache.begin[node]; k < cache.begin[node + 1]; ++k) {
        if (m_faceInPatch[cache.faces[k]] == 2) m_faceInPatch[cache.faces[k]] = 0;  // looked at, away: take it now
        addPatchFace(softBody, cache, cache.faces[k]);
      }
    }
    if (m_patchFaces.size() == facesBefore) break;
  }
  return counts;
}

// Under a large turn the chord and the arc disagree on some features, and the stage moves them
// only when both readings agree (Separation.h). A piece that was outside a closed body at the
// start and whose centre ends inside it shows that a path was read wrong. When the arc spared
// features, they were the way in: the stage runs again from the solver's positions with the chord
// alone. When neither reading found the way in, or the chord did not close it, the faces crossed on
// the arc are carried with the piece from where they stood in its frame at the start
// (carryCrossedFaces). A piece inside at the start (a body folded round it) is left to the stage.
// The winding number visits every face of the body, and only for a turning piece near a closed
// body.
void SoftBodySolverImpl::keepOutsideClosedBody(Tool& tool, const ToolModel& piece, const PieceMotion& motion,
                                           const btSoftBody& softBody, const SoftBodyCache& cache,
                                           const std::vector<NearPiece>& near, SeparationCounts& counts) {
  const Vec3 centre = piece.bounds.center();
  const auto endsInside = [&] {
    const auto endOf = [&](Index id) {
      const Index vertex = m_vertexOfNode[id];
      return vertex != kInvalidIndex ? m_patch.positions[vertex] : toVec3(softBody.m_nodes[static_cast<int>(id)].m_x);
    };
    return std::abs(windingNumber(softBody, motion.end().apply(centre), endOf)) > Real(0.5);
  };
  const auto startOf = [&](Index id) { return toVec3(softBody.m_nodes[static_cast<int>(id)].m_q); };
  if (!endsInside() || std::abs(windingNumber(softBody, motion.start().apply(centre), startOf)) > Real(0.5)) return;
  if (counts.arcSpared > 0) {
    for (Index v = 0; v < m_patch.vertexCount(); ++v) {
      m_patch.positions[v] = m_patch.solvedPositions[v];
      m_patch.moved[v] = 0;
    }
    const SeparationCounts bothReadings = counts;
    counts = separateGrowingPatch(tool, piece, motion.alongChord(), softBody, cache, Stage::Rounds, near);
    counts.nodesMoved += bothReadings.nodesMoved;
    counts.facesMoved += bothReadings.facesMoved;
    if (!endsInside()) return;
  }
  const SeparationCounts carried = carryCrossedFaces(piece, motion, tool.state().options.separation, m_patch);
  m_carried = m_carried || carried.nodesMoved > 0;
  counts.nodesMoved += carried.nodesMoved;
  counts.nodesInside = carried.nodesInside;
  counts.facesPierced = carried.facesPierced;
}

SeparationCounts SoftBodySolverImpl::separatePiece(Tool& tool, const ToolModel& piece, const PieceMotion& motion,
                                               btSoftBody& softBody, Stage stage,
                                               const std::vector<NearPiece>& near) {
  const Real clearance = tool.state().options.separation.clearance;
  const Aabb swept = sweptBounds(piece.bounds, motion).expanded(clearance);
  const int nodeCount = softBody.m_nodes.size();

  // Gather: the nodes whose moves this step meet the piece's reach, and the faces whose boxes
  // (their nodes at both ends of the step) meet it, found among the faces of the nodes near the
  // reach grown by the cache's face reach, with the faces' nodes.
  SoftBodyCache& cache = cacheOf(softBody);
  // The faces' reach as the solve left them, and what the last word's moves in this step added.
  const Real faceReach = cache.faceReach + cache.lastWordReach;
  const Aabb grown = swept.expanded(faceReach);
  m_patch.clear();
  m_nearNodes.clear();
  // A dynamic tool takes the moved nodes' reaction, and the body's pinned nodes stop it, near this
  // step's reach or not: a fast tool reaches next step what it does not reach in this one.
  const Real inverseStep = Real(softBody.m_sst.isdt);
  detail::DynamicBody dynamicTool = reactingBody(tool.state());
  if (cache.boundsHold && !grown.overlaps(cache.bounds)) {
    if (dynamicTool) {
      stopAtPinnedNodes(dynamicTool, piece, motion.end(), inverseStep, cache, softBody,
                        tool.state().lastWord.nonFiniteWrites);
    }
    return {};
  }
  const auto gatherNode = [&](Index i) {
    const btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(i)];
    if (!segmentMeets(grown, node.m_q, node.m_x)) return;
    m_nearNodes.push_back(i);
    if (segmentMeets(swept, node.m_q, node.m_x)) patchVertexOf(softBody, cache, i);
  };
  if (cache.candidatesHold && faceReach <= cache.candidateReach) {
    // In the nodes' order, as a walk over all of them would meet them: the patch, and so the
    // stage's arithmetic, does not depend on how the gather found its nodes.
    if (!cache.candidatesSorted) std::sort(cache.candidates.begin(), cache.candidates.end());
    cache.candidatesSorted = true;
    for (const Index i : cache.candidates) gatherNode(i);
  } else {
    for (Index i = 0; i < static_cast<Index>(nodeCount); ++i) gatherNode(i);
  }
  m_patchFaces.clear();
  // Faces looked at and found away are marked 2 for the rest of the gather, so each is boxed once.
  // A face's box reaches no further than the face reach from any of its nodes: a face with a node
  // that is not near cannot meet the piece's reach, and is not boxed. Nor is one with a node whose
  // move meets the piece's reach (a patch vertex so far, marked 2): its box holds that move.
  for (const Index node : m_nearNodes) m_isNearNode[node] = m_vertexOfNode[node] != kInvalidIndex ? 2 : 1;
  for (const Index node : m_nearNodes) {
    for (Index k = cache.begin[node]; k < cache.begin[node + 1]; ++k) {
      const Index f = cache.faces[k];
      if (m_faceInPatch[f] != 0) continue;
      const std::array<Index, 3>& corners = cache.faceNodes[f];
      const unsigned char nearness[3] = {m_isNearNode[corners[0]], m_isNearNode[corners[1]], m_isNearNode[corners[2]]};
      if (nearness[0] == 0 || nearness[1] == 0 || nearness[2] == 0) continue;
      if (nearness[0] == 2 || nearness[1] == 2 || nearness[2] == 2) {
        addPatchFace(softBody, cache, f);
        continue;
      }
      Aabb box;
      for (const Index n : corners) {
        const btSoftBody::Node& corner = softBody.m_nodes[static_cast<int>(n)];
        box.include(toVec3(corner.m_x));
        box.include(toVec3(corner.m_q));
      }
      if (swept.overlaps(box)) {
        addPatchFace(softBody, cache, f);
      } else {
        m_faceInPatch[f] = 2;
        m_patchFaces.push_back(f);
      }
    }
  }
  for (const Index node : m_nearNodes) m_isNearNode[node] = 0;
  if (m_patch.vertexCount() == 0) {
    for (Index f : m_patchFaces) m_faceInPatch[f] = 0;
    if (dynamicTool) {
      stopAtPinnedNodes(dynamicTool, piece, motion.end(), inverseStep, cache, softBody,
                        tool.state().lastWord.nonFiniteWrites);
    }
    return {};
  }
  ++m_piecesNear;

  SeparationCounts counts = separateGrowingPatch(tool, piece, motion, softBody, cache, stage, near);
  if (stage == Stage::Rounds && cache.closed && motion.samples() > 1) {
    keepOutsideClosedBody(tool, piece, motion, softBody, cache, near, counts);
  }
  for (Index f : m_patchFaces) m_faceInPatch[f] = 0;
  THINTOOL_ASSERT(m_patch.faces.size() <= m_patchFaces.size());

  // Scatter the moves. A moved node's velocity along its move is what the solve gave it, or the
  // tool's own there, whichever separates faster: a contact without bounce. Taking the move itself
  // as velocity, as Bullet's position solve would, turns every correction of the solver's overlap
  // into a kick away from the tool.
  if (dynamicTool) findBackings(softBody);
  const detail::BodyVelocities toolBefore(dynamicTool);
  bool movedAny = false;
  Real largestMove = 0;
  for (Index v = 0; v < m_patch.vertexCount(); ++v) {
    const Index id = m_patch.nodeIds[v];
    THINTOOL_ASSERT(id < static_cast<Index>(nodeCount) && m_vertexOfNode[id] == v);
    m_vertexOfNode[id] = kInvalidIndex;
    if (m_patch.moved[v] == 0 || !isFinite(m_patch.positions[v])) {
      continue;
    }
    if (cache.candidatesHold && cache.isCandidate[id] == 0) {
      cache.isCandidate[id] = 1;
      cache.candidates.push_back(id);
      cache.candidatesSorted = false;
    }
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(id)];
    const btVector3 moved = toBt(m_patch.positions[v]);
    const btVector3 displacement = moved - node.m_x;
    largestMove = std::max(largestMove, Real(displacement.length()));
    cache.bounds.include(toVec3(moved));
    const btVector3 positionBefore = node.m_x;
    const btVector3 velocityBefore = node.m_v;
    if (cache.motionSolved && cache.isChanged[id] == 0) {
      cache.isChanged[id] = 1;
      cache.changed.push_back(id);
    }
    node.m_x = moved;
    const Vec3& normal = m_patch.directions[v];
    const Vec3 toolPoint = m_patch.positions[v];
    const Vec3 toolVelocity = (toolPoint - motion.start().apply(motion.end().applyInverse(toolPoint))) * inverseStep;
    const btVector3 solvedVelocity = node.m_v;
    const Vec3 velocity = toVec3(node.m_v);
    const Real along = dot(velocity, normal);
    const Vec3 separated = velocity + normal * (std::max(along, dot(toolVelocity, normal)) - along);
    Vec3 momentumTaken;  // the node's change of momentum, whose opposite the tool takes (N s)
    if (isFinite(separated)) {
      node.m_v = toBt(separated);
      if (node.m_im > 0) {
        momentumTaken = (velocity - separated) / Real(node.m_im);
        addToHoldWrench(tool.state(), toolPoint, momentumTaken * inverseStep);
      }
    }
    detail::checkWrite(positionBefore, node.m_x, tool.state().lastWord.nonFiniteWrites);
    detail::checkWrite(velocityBefore, node.m_v, tool.state().lastWord.nonFiniteWrites);
    movedAny = true;
    if (m_deformable) {
      // After Bullet's deformable solve and its applyTransforms a move carries no momentum of its
      // own: the tool takes the node's change of momentum, no more. Counting the move's speed as
      // the closing speed, a multibody gripper's fingers holding a cube by the last word alone
      // were pushed down with seven times its weight.
      if (dynamicTool && node.m_im > 0 && momentumTaken != Vec3{}) {
        dynamicTool.applyImpulse(toBt(momentumTaken), toBt(toolPoint));
      }
    } else if (dynamicTool && node.m_im > 0) {
      const int backing = m_backingOfNode[id];
      reactOnTool(dynamicTool, softBody, node, backing >= 0 ? &softBody.m_rcontacts[backing] : nullptr,
                  displacement, solvedVelocity);
    }
  }
  if (dynamicTool) {
    toolBefore.check(tool.state().lastWord.nonFiniteWrites);
    stopAtPinnedNodes(dynamicTool, piece, motion.end(), inverseStep, cache, softBody,
                      tool.state().lastWord.nonFiniteWrites);
    for (int c = 0; c < softBody.m_rcontacts.size(); ++c) {
      m_backingOfNode[static_cast<Index>(softBody.m_rcontacts[c].m_node - &softBody.m_nodes[0])] = -1;
    }
  }
  // A face's box grows by at most twice its nodes' largest move: the gathers after this one reach
  // that much further for the faces the move stretched.
  cache.lastWordReach += 2 * largestMove;
  if (movedAny) {
    softBody.activate();
    if (dynamicTool) dynamicTool.activate();
  }
  return counts;
}

}  // namespace detail
}  // namespace thintool
