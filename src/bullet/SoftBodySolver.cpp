// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/SoftBodySolver.h>

#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace thintool {

namespace {

Aabb worldBounds(const Aabb& local, const Pose& pose) {
  Aabb box;
  for (int corner = 0; corner < 8; ++corner) {
    box.include(pose.apply({(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                            (corner & 4) ? local.max.z : local.min.z}));
  }
  return box;
}

// Everything the piece can reach during the step: its boxes at both ends and, when it turns, the
// spheres round its centre at both ends, which hold every pose of the arc in between.
Aabb sweptBounds(const Aabb& local, const PieceMotion& motion) {
  Aabb box = worldBounds(local, motion.start());
  box.include(worldBounds(local, motion.end()));
  if (motion.turn() > 0) {
    const Real radius = length(local.extent()) / 2;
    box.include(Aabb{motion.start().apply(local.center()), motion.start().apply(local.center())}.expanded(radius));
    box.include(Aabb{motion.end().apply(local.center()), motion.end().apply(local.center())}.expanded(radius));
  }
  return box;
}

bool ignores(const btSoftBody& softBody, const btCollisionObject& body) {
  return softBody.m_collisionDisabledObjects.findLinearSearch(&body) != softBody.m_collisionDisabledObjects.size();
}

}  // namespace

SoftBodySolver::SoftBodySolver(CollisionConfiguration& configuration) : m_configuration(configuration) {}

void SoftBodySolver::solveConstraints(btScalar timeStep) {
  btDefaultSoftBodySolver::solveConstraints(timeStep);
  for (Tool* tool : m_configuration.tools()) {
    separate(*tool);
  }
}

void SoftBodySolver::separate(Tool& tool) {
  tool.m_lastWord = LastWordDiagnostics{};
  const SeparationSettings& settings = tool.m_options.separation;
  const Pose now = toPose(tool.body().getWorldTransform());
  if (!settings.enabled || !isFinite(now)) {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const Pose before = tool.m_hasSeparatedPose && !tool.m_separationJump ? tool.m_separatedPose : now;
  for (Index p = 0; p < tool.pieceCount(); ++p) {
    const PieceMotion motion(before * tool.pieceTransform(p), now * tool.pieceTransform(p), settings.maxTurnPerSample);
    for (int s = 0; s < m_softBodySet.size(); ++s) {
      btSoftBody& softBody = *m_softBodySet[s];
      if (!ignores(softBody, tool.body())) {
        tool.m_lastWord.counts.accumulate(separatePiece(tool, tool.piece(p), motion, softBody));
      }
    }
  }
  tool.m_separatedPose = now;
  tool.m_hasSeparatedPose = true;
  tool.m_separationJump = false;
  tool.m_lastWord.ran = true;
  tool.m_lastWord.microseconds =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

SeparationCounts SoftBodySolver::separatePiece(Tool& tool, const ToolModel& piece, const PieceMotion& motion,
                                               btSoftBody& softBody) {
  const Real clearance = tool.m_options.separation.clearance;
  const Aabb swept = sweptBounds(piece.bounds, motion).expanded(clearance);
  const int nodeCount = softBody.m_nodes.size();
  if (m_vertexOfNode.size() < static_cast<std::size_t>(nodeCount)) {
    m_vertexOfNode.resize(static_cast<std::size_t>(nodeCount), kInvalidIndex);
  }

  // Gather: the nodes and the faces whose moves this step meet the piece's reach, with the faces'
  // nodes.
  m_patch.clear();
  const btSoftBody::Node* first = nodeCount > 0 ? &softBody.m_nodes[0] : nullptr;
  const auto vertexOf = [&](const btSoftBody::Node& node) {
    const auto id = static_cast<Index>(&node - first);
    Index& vertex = m_vertexOfNode[id];
    if (vertex == kInvalidIndex) {
      vertex = m_patch.addVertex(id, toVec3(node.m_q), toVec3(node.m_x), Real(node.m_im));
    }
    return vertex;
  };
  for (int i = 0; i < nodeCount; ++i) {
    const btSoftBody::Node& node = softBody.m_nodes[i];
    if (swept.overlaps(Aabb::fromPoints(toVec3(node.m_q), toVec3(node.m_x)))) {
      vertexOf(node);
    }
  }
  for (int f = 0; f < softBody.m_faces.size(); ++f) {
    const btSoftBody::Face& face = softBody.m_faces[f];
    Aabb box;
    for (const btSoftBody::Node* node : face.m_n) {
      box.include(toVec3(node->m_x));
      box.include(toVec3(node->m_q));
    }
    if (swept.overlaps(box)) {
      m_patch.faces.push_back({vertexOf(*face.m_n[0]), vertexOf(*face.m_n[1]), vertexOf(*face.m_n[2])});
    }
  }
  if (m_patch.vertexCount() == 0) {
    return {};
  }

  const SeparationCounts counts = separateFromPiece(piece, motion, tool.m_options.separation, m_patch);

  // Scatter the moves, with velocities as Bullet's position solve sets them.
  const btScalar velocityScale = softBody.m_sst.isdt * (1 - softBody.m_cfg.kDP);
  btRigidBody* dynamicTool = tool.body().isStaticOrKinematicObject() ? nullptr : &tool.body();
  bool movedAny = false;
  for (Index v = 0; v < m_patch.vertexCount(); ++v) {
    const Index id = m_patch.nodeIds[v];
    m_vertexOfNode[id] = kInvalidIndex;
    if (m_patch.moved[v] == 0 || !isFinite(m_patch.positions[v])) {
      continue;
    }
    btSoftBody::Node& node = softBody.m_nodes[static_cast<int>(id)];
    const btVector3 moved = toBt(m_patch.positions[v]);
    const btVector3 displacement = moved - node.m_x;
    node.m_x = moved;
    node.m_v = (node.m_x - node.m_q) * velocityScale;
    movedAny = true;
    if (dynamicTool != nullptr && node.m_im > 0) {
      // The node's change of momentum, taken from the tool.
      dynamicTool->applyImpulse(displacement * (-softBody.m_sst.isdt / node.m_im),
                                node.m_x - dynamicTool->getCenterOfMassPosition());
    }
  }
  if (movedAny) {
    softBody.activate();
    if (dynamicTool != nullptr) dynamicTool->activate();
  }
  return counts;
}

}  // namespace thintool
