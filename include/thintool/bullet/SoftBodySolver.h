// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The last word: a soft-body solver to pass to btSoftRigidDynamicsWorld or
/// btSoftMultiBodyDynamicsWorld where btDefaultSoftBodySolver was.
///
///     thintool::CollisionConfiguration configuration;
///     thintool::SoftBodySolver softBodySolver(configuration);
///     btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &constraintSolver, &configuration,
///                                    &softBodySolver);
///
/// Bullet runs the world's soft-body solver after the collision pass, and the solver moves the
/// nodes again (links, pressure, its own contacts): whatever the collision pass did, the soft
/// solver has the last word on where a node ends the step. This one runs Bullet's own solve
/// unchanged, then, for every tool of the configuration whose ToolOptions::separation is enabled,
/// puts every soft node and face near the tool back on its side (response/Separation.h) and sets
/// the moved nodes' velocities as Bullet's solve does, v = (x − x_start)·(1 − kDP)/dt. A dynamic
/// tool receives the moved nodes' reaction as impulses. Soft bodies that ignore the tool
/// (m_collisionDisabledObjects) are left alone. Tool::report() says what the stage did and what
/// it left (ToolDiagnostics::lastWord).

#include <thintool/response/Separation.h>

#include <BulletSoftBody/btDefaultSoftBodySolver.h>

#include <vector>

class btSoftBody;

namespace thintool {

class CollisionConfiguration;
class Tool;

class SoftBodySolver : public btDefaultSoftBodySolver {
 public:
  /// configuration: the world's, whose tools get the last word; it must outlive the solver.
  explicit SoftBodySolver(CollisionConfiguration& configuration);

  // See: btDefaultSoftBodySolver::solveConstraints
  void solveConstraints(btScalar timeStep) override;

 private:
  // One pass of the tool's pieces over the soft bodies; returns whether it moved anything.
  bool separate(Tool& tool);
  SeparationCounts separatePiece(Tool& tool, const ToolModel& piece, const PieceMotion& motion, btSoftBody& softBody);

  // Soft node -> its faces (CSR), per soft body, rebuilt when its node or face count changes.
  struct FaceAdjacency {
    const btSoftBody* softBody = nullptr;
    Index nodeCount = kInvalidIndex;
    Index faceCount = kInvalidIndex;
    std::vector<Index> begin;
    std::vector<Index> faces;
  };
  const FaceAdjacency& adjacencyOf(const btSoftBody& softBody);

  static constexpr int kMostPasses = 4;
  static constexpr int kMostExtensions = 4;

  CollisionConfiguration& m_configuration;
  std::vector<Tool*> m_active;  // tools whose stage runs this step
  int m_piecesNear = 0;         // (piece, soft body) pairs with soft features near, this pass
  SeparationPatch m_patch;
  std::vector<Index> m_vertexOfNode;  // soft node -> patch vertex, kInvalidIndex when absent
  std::vector<unsigned char> m_faceInPatch;  // soft face -> whether the patch has it
  std::vector<Index> m_patchFaces;           // the soft faces the patch has
  std::vector<FaceAdjacency> m_adjacency;
};

}  // namespace thintool
