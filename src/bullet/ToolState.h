// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// What a thintool::Tool keeps behind its public face: its models, its pairs with soft bodies, its
// view of the motion and the report it is building. The glue's stages reach it through
// Tool::state().

#include "DynamicBody.h"
#include "PairState.h"
#include "detection/SweptDetection.h"
#include "force/ContactForce.h"
#include "tool/ToolModel.h"

#include <thintool/bullet/Tool.h>

#include <memory>
#include <vector>

class btRigidBody;
class btSoftBody;

namespace thintool::detail {

class CollisionPass;
class SweptProxy;

struct ToolState {
  ToolState(btCollisionObject& toolBody, const ToolOptions& toolOptions, std::vector<ToolModel> toolPieces,
            std::vector<Pose> toolPieceTransforms);
  ~ToolState();

  /// The body when it is a dynamic btRigidBody, which takes the tissue's reaction; else null.
  btRigidBody* dynamicBody() const;
  /// The body when the tissue's reaction moves it, a dynamic btRigidBody or a multibody's link;
  /// else empty.
  DynamicBody dynamic() const;
  PairState& pairState(btSoftBody& softBody, Index piece);
  /// The soft body's rest shape, captured now if it has none or its node count changed.
  RestShape& restShape(const btSoftBody& softBody);
  /// Swept detection's view of the tool's motion in this step: the body's pose at its start and at
  /// its end. Kinematic and static tools: the pose the last time the proxy's box was updated, and
  /// now. Dynamic tools: Bullet's pose now and its unconstrained prediction for the step's end (a
  /// multibody link's from its velocity, DynamicBody::predictLinkPose).
  void bodyMotion(Pose& outPrevious, Pose& outCurrent) const;
  /// Called once per simulation step, when Bullet updates the proxy's box: moves "now" to "before".
  void trackMotion();

  btCollisionObject& body;
  ToolOptions options;
  std::vector<ToolModel> pieces;
  std::vector<Pose> pieceTransforms;
  std::vector<std::unique_ptr<PairState>> pairs;
  struct SoftRest {
    const btSoftBody* softBody = nullptr;
    RestShape shape;
  };
  std::vector<std::unique_ptr<SoftRest>> restShapes;
  /// With swept detection: the collision object whose box is the tool's swept box, so that Bullet
  /// makes a pair with every soft body the tool sweeps past (the tool's own box is not swept).
  /// Owned by the tool, but it is in the world's object array, which Bullet programs free at exit
  /// object by object: deleted there, it tells the tool (SweptProxy's destructor), which then does
  /// not delete it again.
  SweptProxy* proxy = nullptr;
  Pose poseBefore;
  Pose poseNow;
  bool motionTracked = false;
  bool jumpNext = false;
  SweptWorkspace sweptWorkspace;
  ToolStepReport report;
  /// The last word's view of the motion: the body's pose when the stage last ran (the start of
  /// this step), whether it has one, and whether resetMotion() declared the next move a jump.
  Pose separatedPose;
  bool hasSeparatedPose = false;
  bool separationJump = false;
  LastWordDiagnostics lastWord;
  mutable JacobianScratch jacobianScratch;  // a multibody link's reactions
  /// The impulses ThinTool applied to the dynamic tool since the soft-body solver began this step
  /// (SoftBodySolver::predictMotion), and that step's length (s; 0 before the first).
  mutable AppliedImpulse applied;
  btScalar stepLength = 0;
  Wrench holdWrench;  // this step's, torque about the world's origin
  Index holdNodesShared = 0;
  /// Node contacts given to Bullet's deformable solve this step (ToolDiagnostics).
  Index deformableNodeContacts = 0;
  Pose lastFiniteBodyPose;  // the report's frame when the body's transform is not finite
  /// The configuration's record of the current collision pass; null for a tool made without one.
  CollisionPass* pass = nullptr;
};

}  // namespace thintool::detail
