// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "response/Response.h"

#include "geometry/Ccd.h"

#include <thintool/core/Assert.h>

#include <algorithm>
#include <array>
#include <limits>

namespace thintool {

namespace {

// How far inside the tool grown by the skin a node may lie and still count as on its surface (m):
// a node the projection put on that surface, give or take rounding.
constexpr Real kOnGrownSurface = 1e-9;

// How far a node now at position lies inside the tool grown by the skin, measured from the face
// it was outside of at the start of the step (at previousPosition, in the tool's previous pose),
// with that face's normal in the world: the move that sends it back out the side it came from.
// Not positive when the node is outside.
Real depthBehindEntryFace(const ToolModel& model, const Pose& toolPose, const Pose& previousToolPose,
                          const Vec3& previousPosition, const Vec3& position, Real skin, Vec3& outNormal) {
  const Vec3 local = toolPose.applyInverse(position);
  if (outsideDistance(model.planes, local) >= skin) {
    return 0;
  }
  Index entry = 0;
  outsideDistance(model.planes, previousToolPose.applyInverse(previousPosition), &entry);
  outNormal = toolPose.applyToDirection(model.planes[entry].normal);
  return skin - model.planes[entry].signedDistance(local);
}

// The tool face through which a node's straight path over the step, from start (tool frame at the
// step's start) to end (tool frame now), enters the tool grown by the skin and then leaves it again:
// the side it came from, when the response carried it across or round the tool. kInvalidIndex when
// the path misses the tool, ends inside it, or starts inside it. A node that starts in the skin is
// tested against the tool grown by half its distance, so that it starts outside.
Index planeMovedThrough(const ToolModel& model, const Vec3& start, const Vec3& end, Real skin) {
  // Most moved nodes stay in front of one face: the clip against the whole skin rejects them at
  // that face, and a path that misses it misses any thinner skin too.
  ClipResult path = clipSegmentConvex(model.planes, skin, start, end);
  if (!path.hit) {
    return kInvalidIndex;
  }
  const Real grow = std::min(skin, outsideDistance(model.planes, start) / 2);
  if (!(grow > 0)) {
    return kInvalidIndex;
  }
  if (grow < skin) {
    path = clipSegmentConvex(model.planes, grow, start, end);
  }
  return path.hit && path.leavePlane != kInvalidIndex ? path.enterPlane : kInvalidIndex;
}

// How far each of a contact's nodes moves along its normal so that the contact point, their
// barycentric mix, moves depth: in proportion to weight × inverse mass, the smallest mass-weighted
// move. Beside a pinned node, though, a free node moves no further than the point itself, nor past
// the contact's plane (room: how far each node lies behind it): a point there (weight 0.01 on the
// free node) would need its free node moved a hundred times its depth, a kick of metres in a step,
// and the point hardly moves, so that every further contact and sweep would push the node again.
// Nodes at that bound move their bound and the others share what is left; the point may then move
// less than depth, and the last word answers for the rest. False when no node can move.
bool shareContactMove(const PatchContact& contact, const std::vector<Real>& inverseMasses, Real depth,
                      const std::array<Real, 3>& room, std::array<Real, 3>& outShares) {
  std::array<bool, 3> atBound{};
  bool pinned = false;
  for (Index k = 0; k < contact.softNodeCount; ++k) pinned = pinned || !(inverseMasses[contact.patchVertices[k]] > 0);
  std::array<Real, 3> most;
  for (Index k = 0; k < 3; ++k) {
    most[k] = pinned ? std::min(depth, std::max(room[k], Real(0))) : std::numeric_limits<Real>::max();
  }
  for (int round = 0; round < 3; ++round) {
    Real left = depth;
    Real weightedMobility = 0;
    for (Index k = 0; k < contact.softNodeCount; ++k) {
      if (atBound[k]) {
        left -= contact.barycentric[k] * most[k];
      } else {
        weightedMobility += contact.barycentric[k] * contact.barycentric[k] * inverseMasses[contact.patchVertices[k]];
      }
    }
    bool capped = false;
    for (Index k = 0; k < contact.softNodeCount; ++k) {
      if (atBound[k]) {
        outShares[k] = most[k];
        continue;
      }
      const Real mobility = contact.barycentric[k] * inverseMasses[contact.patchVertices[k]];
      outShares[k] = weightedMobility > 0 && left > 0 ? left * mobility / weightedMobility : 0;
      if (outShares[k] > most[k]) {
        atBound[k] = true;
        capped = true;
      }
    }
    if (!capped) break;
  }
  bool any = false;
  for (Index k = 0; k < contact.softNodeCount; ++k) {
    outShares[k] = std::min(outShares[k], most[k]);
    any = any || outShares[k] > 0;
  }
  return any;
}

// The normal (world) of the tool face that points most nearly along direction. Friction reads a
// node's slip in that face's plane and its normal move across it: read across the soft face's
// normal that a tool's edge or corner pushed the node along, its plane turned from face to face,
// and each step's push, kept whole by sticking, fed a ball held under a plate (`stability`,
// 1/10,000 s: the held energy grew from 0.61 to 3.2 J).
Vec3 toolFaceAlong(const StepContext& step, const Vec3& direction) {
  Vec3 best = direction;
  Real bestDot = -std::numeric_limits<Real>::max();
  for (const Plane& plane : step.model.planes) {
    const Vec3 normal = step.pose.applyToDirection(plane.normal);
    const Real along = dot(normal, direction);
    if (along > bestDot) {
      bestDot = along;
      best = normal;
    }
  }
  return best;
}

// Friction for each moved node (FrictionSettings). The tool's surface motion at a node is that of
// the tool point where the node now is, from the previous pose to this one.
void applyFriction(const StepContext& step, const FrictionSettings& friction, const SoftPatch& patch,
                   std::vector<Vec3>& positions, std::vector<NodeCorrection>& corrections) {
  for (NodeCorrection& correction : corrections) {
    const Index vertex = correction.vertex;
    Vec3& position = positions[vertex];
    const Vec3 frictionNormal = toolFaceAlong(step, correction.normal);
    const Real normalMove = dot(position - patch.positions[vertex], frictionNormal);
    if (!(normalMove > 0)) {
      continue;
    }
    const Vec3 surfaceMove = position - step.previousPose.apply(step.pose.applyInverse(position));
    const Vec3 relative = position - patch.previousPositions[vertex] - surfaceMove;
    const Vec3 tangential = relative - frictionNormal * dot(relative, frictionNormal);
    const Real slip = length(tangential);
    if (!(slip > 0)) {
      continue;
    }
    if (slip <= friction.staticCoefficient * normalMove) {
      position -= tangential;
      correction.sticks = true;
    } else {
      position -= tangential * std::min<Real>(1, friction.kineticCoefficient * normalMove / slip);
    }
  }
}

}  // namespace

// One call of computeResponse: the step, its inputs, and the node positions as the stages move
// them. A node gets a slot, an entry in the output, the first time a stage moves it.
struct ResponseProjection {
  const StepContext& step;
  const SoftPatch& patch;
  const std::vector<PatchContact>& contacts;
  ResponseWorkspace& work;
  std::vector<NodeCorrection>& corrections;

  void begin();
  NodeCorrection& slotOf(Index vertex);
  const Vec3& positionOf(Index vertex) const {
    return work.m_slot[vertex] == kInvalidIndex ? patch.positions[vertex] : work.m_positions[vertex];
  }
  bool movable(Index vertex) const { return patch.inverseMasses[vertex] > 0; }
  // The skin a soft point keeps this step: all of it for a point that began the step beyond the
  // skin; for one that began inside it, where it began plus skinGrowthSpeed·dt, so that the
  // projection never throws it out faster than that.
  Real skinFrom(const Vec3& startPosition) const {
    const Real start = outsideDistance(step.model.planes, step.previousPose.applyInverse(startPosition));
    return std::min(step.skin, std::max(start, Real(0)) + step.skinGrowthSpeed * step.dt);
  }
  // Signed distance in front of the contact's plane, moved back to the skin the point keeps.
  Real distanceOf(const PatchContact& contact, const Vec3& position) const {
    return dot(contact.normal, position) + contact.offset + work.m_contactSkinLeft[&contact - contacts.data()];
  }

  void pushByPaperForce(Real stiffness);
  void leaveThroughEntryPlanes();
  void guardStrayNodes();
  void moveChosenNodesOut();
  void projectContactPoints();
  void returnCarriedNodes();
  void slideWithFriction(const FrictionSettings& friction) {
    applyFriction(step, friction, patch, work.m_positions, corrections);
  }
  Real justifiedMove(Index vertex, Real pieceReach) const;
  Index finish(Wrench& outWrench);
};

void ResponseProjection::begin() {
  const Index vertexCount = patch.vertexCount();
  if (work.m_slot.size() < vertexCount) {
    work.m_slot.resize(vertexCount, kInvalidIndex);
  }
  work.m_positions.resize(vertexCount);
  work.m_largestShare.clear();
  work.m_entryDepth.clear();
  work.m_contactSkinLeft.clear();
  for (const PatchContact& contact : contacts) {
    // A face's or an edge's contact point is wherever the tool meets it this step, not a point
    // of the soft body that has a place at the start of the step: it keeps the whole skin.
    const bool node = contact.kind == ContactKind::SoftNode;
    work.m_contactSkinLeft.push_back(node ? step.skin - skinFrom(patch.previousPositions[contact.patchVertices[0]])
                                          : 0);
  }
}

NodeCorrection& ResponseProjection::slotOf(Index vertex) {
  THINTOOL_ASSERT(vertex < patch.vertexCount());
  if (work.m_slot[vertex] == kInvalidIndex) {
    work.m_slot[vertex] = static_cast<Index>(corrections.size());
    work.m_positions[vertex] = patch.positions[vertex];
    NodeCorrection correction;
    correction.vertex = vertex;
    corrections.push_back(correction);
    work.m_largestShare.push_back(0);
    work.m_entryDepth.push_back(0);
  }
  return corrections[work.m_slot[vertex]];
}

// The paper's eq. (2) as the displacement it causes within the step (see the file's comment).
void ResponseProjection::pushByPaperForce(Real stiffness) {
  for (const PatchContact& contact : contacts) {
    const Real pushForce = stiffness * (contact.depth + step.skin);
    for (Index k = 0; k < contact.softNodeCount; ++k) {
      const Index vertex = contact.patchVertices[k];
      if (!movable(vertex)) {
        continue;
      }
      NodeCorrection& correction = slotOf(vertex);
      work.m_positions[vertex] +=
          contact.normal * (pushForce * contact.barycentric[k] * patch.inverseMasses[vertex] * step.dt * step.dt);
      correction.normal = contact.normal;
    }
  }
}

// Soft nodes inside the tool choose the least-violated plane among their contacts': a swept
// contact of the node itself, or the entry plane of a ray that hit one of its faces. Never across
// the tool, never out of its far side. moveChosenNodesOut moves them.
void ResponseProjection::leaveThroughEntryPlanes() {
  for (const PatchContact& contact : contacts) {
    if (contact.kind != ContactKind::ToolRay && contact.kind != ContactKind::SoftNode) {
      continue;
    }
    for (Index k = 0; k < contact.softNodeCount; ++k) {
      const Index vertex = contact.patchVertices[k];
      const Real behind = -distanceOf(contact, patch.positions[vertex]);
      if (!movable(vertex) || !(behind > 0)) {
        continue;
      }
      if (contact.kind == ContactKind::ToolRay &&
          outsideDistance(step.model.planes, step.pose.applyInverse(patch.positions[vertex])) >= step.skin) {
        continue;  // beside the tool: projectContactPoints moves its face
      }
      NodeCorrection& correction = slotOf(vertex);
      Real& chosen = work.m_entryDepth[work.m_slot[vertex]];
      if (chosen == 0 || behind < chosen) {
        chosen = behind;
        correction.normal = contact.normal;
      }
    }
  }
}

// The node guard: nodes inside the tool that no contact speaks for choose the face they entered by.
void ResponseProjection::guardStrayNodes() {
  for (Index vertex = 0; vertex < patch.vertexCount(); ++vertex) {
    if (work.m_slot[vertex] != kInvalidIndex || !movable(vertex)) {
      continue;
    }
    Vec3 normal;
    const Real depth = depthBehindEntryFace(step.model, step.pose, step.previousPose, patch.previousPositions[vertex],
                                            patch.positions[vertex], skinFrom(patch.previousPositions[vertex]), normal);
    if (!(depth > 0)) {
      continue;
    }
    NodeCorrection& correction = slotOf(vertex);
    work.m_entryDepth[work.m_slot[vertex]] = depth;
    correction.normal = normal;
  }
}

void ResponseProjection::moveChosenNodesOut() {
  for (NodeCorrection& correction : corrections) {
    const Index slot = work.m_slot[correction.vertex];
    work.m_positions[correction.vertex] += correction.normal * work.m_entryDepth[slot];
    // A node moved as a whole keeps that direction for the solver's hold.
    work.m_largestShare[slot] = std::numeric_limits<Real>::max();
  }
}

// Every contact's soft point onto its plane (shareContactMove), swept in order until all are out.
void ResponseProjection::projectContactPoints() {
  constexpr int kSweeps = 4;
  constexpr Real kSettled = 1e-6;  // m
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    Real worst = 0;
    for (const PatchContact& contact : contacts) {
      Vec3 point;
      std::array<Real, 3> room{};
      for (Index k = 0; k < contact.softNodeCount; ++k) {
        point += positionOf(contact.patchVertices[k]) * contact.barycentric[k];
        room[k] = -distanceOf(contact, positionOf(contact.patchVertices[k]));
      }
      const Real depth = -distanceOf(contact, point);
      std::array<Real, 3> shares{};
      if (!(depth > 0) || !shareContactMove(contact, patch.inverseMasses, depth, room, shares)) {
        continue;
      }
      worst = std::max(worst, depth);
      for (Index k = 0; k < contact.softNodeCount; ++k) {
        const Index vertex = contact.patchVertices[k];
        const Real share = shares[k];
        if (!(share > 0)) {
          continue;
        }
        NodeCorrection& correction = slotOf(vertex);
        work.m_positions[vertex] += contact.normal * share;
        Real& largest = work.m_largestShare[work.m_slot[vertex]];
        if (share > largest) {
          largest = share;
          correction.normal = contact.normal;
        }
      }
    }
    if (worst <= kSettled) {
      break;
    }
  }
}

// A face's contact moves its nodes along the face's normal, which near a rim can carry a node into
// the tool from a side no contact speaks for: it leaves again as the node guard sends it. Carried
// across the tool, or round its rim, from where the step began, a node goes back to the face it
// came by: contacts and detection's sides are per face, and a face wrapped round a rim can push one
// of its nodes over the tool while the face itself ends on its own side.
void ResponseProjection::returnCarriedNodes() {
  const ToolModel& model = step.model;
  for (NodeCorrection& correction : corrections) {
    const Index vertex = correction.vertex;
    const Vec3 startLocal = step.previousPose.applyInverse(patch.previousPositions[vertex]);
    const Vec3 endLocal = step.pose.applyInverse(work.m_positions[vertex]);
    const Real nodeSkin = skinFrom(patch.previousPositions[vertex]);
    Index entry = kInvalidIndex;
    if (outsideDistance(model.planes, endLocal, &entry) < nodeSkin) {
      outsideDistance(model.planes, startLocal, &entry);
    } else if (model.planes[entry].signedDistance(startLocal) > nodeSkin) {
      entry = kInvalidIndex;  // in front of the same face all along: the path misses the tool
    } else {
      entry = planeMovedThrough(model, startLocal, endLocal, nodeSkin);
    }
    if (entry != kInvalidIndex) {
      const Plane& face = model.planes[entry];
      const Vec3 faceNormal = step.pose.applyToDirection(face.normal);
      work.m_positions[vertex] += faceNormal * (nodeSkin - face.signedDistance(endLocal));
      correction.normal = faceNormal;
    }
  }
}

// The longest move a correction of this vertex can need (m): back along its own motion this step
// (from where the sweep began it), and pieceReach: across the piece and out of its skin, and as far
// as a point of the piece travelled (its translation and, turning, twice its extent).
Real ResponseProjection::justifiedMove(Index vertex, Real pieceReach) const {
  Real ownMotion = length(patch.positions[vertex] - patch.previousPositions[vertex]);
  if (patch.checkedPositions.size() == patch.vertexCount()) {
    ownMotion = std::max(ownMotion, length(patch.positions[vertex] - patch.checkedPositions[vertex]));
  }
  return pieceReach + ownMotion;
}

// Displacements, the reaction on the tool, and the slots cleared for the next call. A correction
// that is not finite, or moves its node farther than the step can justify, is a fault, not a
// correction: it is dropped here, so that neither the moves, the holds, the reaction nor the next
// step's sweep sees it.
Index ResponseProjection::finish(Wrench& outWrench) {
  const Real inverseDtSquared = 1 / (step.dt * step.dt);
  const Real pieceReach = 2 * length(step.model.bounds.extent()) +
                          length(step.pose.translation - step.previousPose.translation) + step.skin;
  Index kept = 0;
  Index dropped = 0;
  for (Index i = 0; i < static_cast<Index>(corrections.size()); ++i) {
    NodeCorrection correction = corrections[i];
    const Index vertex = correction.vertex;
    work.m_slot[vertex] = kInvalidIndex;
    correction.displacement = work.m_positions[vertex] - patch.positions[vertex];
    const Real justified = justifiedMove(vertex, pieceReach);
    if (!isFinite(correction.displacement) || !isFinite(correction.normal) ||
        !(lengthSquared(correction.displacement) <= justified * justified)) {
      ++dropped;
      continue;
    }
    const Vec3 forceOnTool = correction.displacement * (-inverseDtSquared / patch.inverseMasses[vertex]);
    outWrench.force += forceOnTool;
    outWrench.torque += cross(patch.positions[vertex] - step.pose.translation, forceOnTool);
    corrections[kept++] = correction;
  }
  corrections.resize(kept);
  return dropped;
}

void computeResponse(const StepContext& step, const SoftPatch& patch, const std::vector<PatchContact>& contacts,
                     const ResponseSettings& settings, ResponseResult& out) {
  THINTOOL_ASSERT(patch.consistent());
  out.corrections.clear();
  out.wrench = Wrench{};
  out.rejected = 0;
  if (settings.kind == ResponseKind::None || !(step.dt > 0)) {
    return;
  }
  ResponseProjection projection{step, patch, contacts, out.workspace, out.corrections};
  projection.begin();
  if (settings.kind == ResponseKind::PaperForce) {
    projection.pushByPaperForce(settings.stiffness);
  } else {
    projection.leaveThroughEntryPlanes();
    if (settings.guardNodes) {
      projection.guardStrayNodes();
    }
    projection.moveChosenNodesOut();
    projection.projectContactPoints();
    projection.returnCarriedNodes();
    if (settings.friction.enabled) {
      projection.slideWithFriction(settings.friction);
    }
  }
  out.rejected = projection.finish(out.wrench);
}

void computeHolds(const StepContext& step, const SoftPatch& patch, bool holdAtToolFaces, ResponseResult& response,
                  std::vector<NodeHold>& outHolds) {
  const ToolModel& model = step.model;
  const Pose& toolPose = step.pose;
  const Pose& previousToolPose = step.previousPose;
  const Real skin = step.skin;
  const std::vector<NodeCorrection>& corrections = response.corrections;
  std::vector<Vec3>& positions = response.workspace.m_positions;
  outHolds.clear();
  for (const NodeCorrection& correction : corrections) {
    THINTOOL_ASSERT(correction.vertex < patch.vertexCount());
    const Vec3 at = patch.positions[correction.vertex] + correction.displacement;
    outHolds.push_back({correction.vertex, correction.normal, -dot(correction.normal, at), correction.sticks});
  }
  if (!holdAtToolFaces) {
    return;
  }
  // A moved node keeps its correction's plane, and the tool face's too: a correction along a soft
  // face's normal gives a plane across the tool's face, which would leave the node free to go
  // through the tool during the solve.
  positions.assign(patch.positions.begin(), patch.positions.end());
  for (const NodeCorrection& correction : corrections) {
    positions[correction.vertex] += correction.displacement;
  }
  for (Index vertex = 0; vertex < patch.vertexCount(); ++vertex) {
    if (!(patch.inverseMasses[vertex] > 0)) {
      continue;
    }
    const Vec3 local = toolPose.applyInverse(positions[vertex]);
    const Vec3 startLocal = previousToolPose.applyInverse(patch.previousPositions[vertex]);
    Index front = kInvalidIndex;
    Real distance = -std::numeric_limits<Real>::max();
    Index sameSide = kInvalidIndex;  // also in front of it at the start of the step
    Real sameSideDistance = -std::numeric_limits<Real>::max();
    for (Index p = 0; p < model.planes.size(); ++p) {
      const Real d = model.planes[p].signedDistance(local) - skin;
      if (d > distance) {
        distance = d;
        front = p;
      }
      if (d > sameSideDistance && model.planes[p].signedDistance(startLocal) - skin >= -kOnGrownSurface) {
        sameSideDistance = d;
        sameSide = p;
      }
    }
    if (front == kInvalidIndex || distance < -kOnGrownSurface) {
      continue;  // inside the grown tool: its faces' contacts speak for it
    }
    // Any face it is in front of separates it from the tool: held behind that plane it cannot
    // enter the tool during the solve, and the plane is chosen anew every step, so a node beside a
    // rim can still wrap around it over several steps. One it was in front of at the start of the
    // step, too, keeps it on the side it came from.
    if (sameSide != kInvalidIndex && sameSideDistance >= -kOnGrownSurface) {
      front = sameSide;
    }
    const Plane& face = model.planes[front];
    const Vec3 normal = toolPose.applyToDirection(face.normal);
    outHolds.push_back({vertex, normal, -dot(normal, toolPose.apply(face.normal * (face.offset + skin))), false});
  }
}

}  // namespace thintool
