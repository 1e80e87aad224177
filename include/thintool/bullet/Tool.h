// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A registered tool: its model, its state across steps, and what happened in the latest step.

#include <thintool/bullet/ToolOptions.h>
#include <thintool/core/Api.h>
#include <thintool/core/Math.h>
#include <thintool/detection/DetectionTypes.h>
#include <thintool/force/ForceTypes.h>
#include <thintool/response/ResponseTypes.h>

#include <memory>
#include <string>
#include <vector>

class btCollisionObject;
class btCollisionWorld;
class btRigidBody;
class btSoftBody;
class btTransform;

namespace thintool {

/// A contact of the latest step, with the soft body and tool piece it belongs to.
struct ToolContact {
  const btSoftBody* softBody = nullptr;
  Index piece = 0;  ///< child of a compound tool; 0 otherwise
  Contact contact;
};

/// A tool node the paper's filters excluded in the latest step (discrete detection only).
struct ToolExcludedNode {
  const btSoftBody* softBody = nullptr;
  Index piece = 0;
  Index toolNode = kInvalidIndex;
  int check = 1;  ///< 1 or 2
};

/// What the last word did in the latest step, over the tool's pieces and soft bodies.
struct LastWordDiagnostics {
  /// False when the world's soft-body solver is not a thintool::SoftBodySolver, or the stage is
  /// switched off: nothing then stops Bullet's solver from leaving nodes inside the tool.
  bool ran = false;
  SeparationCounts counts;  ///< moves made, and violations left (counts.nodesInside, counts.facesPierced)
  /// The stage's time in the step (µs): this tool's passes of the last word, and its share of the
  /// energy guard's (the guard's time, split evenly among the tools that have it on).
  double microseconds = 0;
  /// Of microseconds, the pass over the nodes that the last word's survey shares with Bullet's
  /// velocity update after its solve (as btSoftBody::solveConstraints's), which a step without
  /// ThinTool makes too: what the stage adds to the step is microseconds less about this.
  double sharedPassMicroseconds = 0;
  /// Of microseconds, this tool's share of the energy guard's passes over the guarded soft bodies'
  /// nodes, before Bullet's solve and after the last word: they read every node of such a body.
  double energyGuardMicroseconds = 0;
  /// The energy guard (EnergyGuardSettings), over the soft bodies near the tool: nodes it slowed
  /// to the speed bound, and kinetic energy it took out to meet the energy bound (J).
  Index nodesSlowed = 0;
  double energyRemoved = 0;
  /// Nodes whose move in Bullet's solve the energy guard shortened to its speed bound over the step,
  /// before the last word: a bound on the velocity alone would leave the node where the jump took it.
  Index movesShortened = 0;
  /// Nodes the tool held in the soft solver whose load ToolStepReport::holdWrench leaves out: another
  /// tool or another body's contact held them too, and the solver's move of the node does not say
  /// which took what.
  Index holdNodesShared = 0;
  /// Soft bodies near the tool whose pose-matching frame (btSoftBody::Pose::m_rot, kMT > 0) Bullet's
  /// prediction of this step computed as no rotation, and thintool::SoftBodySolver replaced with
  /// the nearest rotation before the match: a flat body folded over a tool, whose frame Bullet's
  /// polar decomposition cannot find.
  Index poseFramesRepaired = 0;
  /// The stage's, the energy guard's and the frames' repair's writes into Bullet's state that left
  /// a finite value not finite (ToolDiagnostics::nonFiniteWrites).
  Index nonFiniteWrites = 0;
  /// Soft nodes left inside the tool or soft faces left pierced by it after the stage: the
  /// invariant, expected 0.
  Index violations() const { return counts.nodesInside + counts.facesPierced; }
};

/// Pairs of the tool with a soft body that ThinTool leaves to Bullet's stock handler, counted by
/// why. Bullet then collides them as it would without ThinTool, and the last word leaves the soft
/// body alone, except a faceless one: the last word still keeps its nodes out of the tool.
struct StockPairs {
  /// The soft body's solver is not the classic one (btDeformableMultiBodyDynamicsWorld), and the
  /// tool keeps Bullet's node contacts there (a discrete tool, a body without faces, or
  /// BulletSettings::deformableNodeContacts off).
  Index deformableWorld = 0;
  /// The soft body collides with rigid bodies by its clusters (fCollision::CL_RS), whose
  /// impulses ThinTool's node moves would fight.
  Index clusterCollision = 0;
  /// The soft body's flags ask for no node contact with rigid bodies (fCollision::SDF_RS unset).
  Index noRigidContact = 0;
  /// The soft body has no faces (ropes, links-only bodies, volumes without a surface): there is
  /// nothing for a tool's rays and swept tests to meet.
  Index noFaces = 0;
  Index total() const { return deformableWorld + clusterCollision + noRigidContact + noFaces; }
};

struct ToolDiagnostics {
  DetectionCounters detection;  ///< summed over the tool's pieces and soft bodies
  Index pairs = 0;              ///< (piece, soft body) pairs processed in the step
  Index nodesMoved = 0;         ///< soft nodes the response moved
  /// Deepest any contacted soft face's hit point still lies inside the tool after the step's
  /// solve (m), measured from the tool's nearest face: what the soft solver's links and pressure
  /// pushed back in. Measured when the report is read.
  Real maxRemainingPenetration = 0;
  double detectionMicroseconds = 0;
  double responseMicroseconds = 0;
  /// Pairs handed to Bullet's stock handler, by why (StockPairs).
  StockPairs stockPairs;
  /// In the deformable world with BulletSettings::deformableNodeContacts: the node contacts
  /// ThinTool's detection gave Bullet's implicit solve in the step, in place of Bullet's own.
  Index deformableNodeContacts = 0;
  /// Soft nodes whose correction was not written: not finite, or longer than the step can justify
  /// (the node's own motion back, across the piece and its skin, and the piece's travel). Never
  /// expected.
  Index rejectedCorrections = 0;
  /// Pairs skipped because the tool's transform was not finite.
  Index invalidPosePairs = 0;
  /// ThinTool's writes into Bullet's state this step (soft nodes' positions and velocities, the
  /// dynamic tool's velocities) that left a finite value not finite, the last word's included.
  /// Every write refuses values that are not finite: expected 0, and a failed internal check
  /// (core/Assert.h) where those are compiled in.
  Index nonFiniteWrites = 0;
  /// The last word (thintool::SoftBodySolver and response/Separation.h), after the soft solver.
  LastWordDiagnostics lastWord;
};

/// The tissue's force on one soft face in contact (force/ContactForce.h).
struct ToolFaceForce {
  const btSoftBody* softBody = nullptr;
  Index piece = 0;
  FaceForce face;
};

/// The force model's result for the step: zero and empty while ToolOptions::force is off.
struct ToolForce {
  Vec3 force;        ///< net, world (N), on the tool
  Vec3 torque;       ///< about torquePoint, world (N·m)
  Vec3 torquePoint;  ///< ForceSettings::torquePoint in world coordinates at the step's end
  std::vector<ToolFaceForce> faces;
};

class Tool;
struct ToolOptions;

struct ToolStepReport {
  std::vector<ToolContact> contacts;
  /// Nodes whose rays found a face but that check 1 or check 2 excluded.
  std::vector<ToolExcludedNode> excludedNodes;
  ToolDiagnostics diagnostics;
  /// Force (N) and torque about the tool body's origin (N·m) the response put on the tool: the
  /// reaction of the soft nodes it moved, Σ m·Δx/dt².
  Wrench wrench;
  /// Force (N) and torque about the tool body's origin (N·m) that the soft solver's stage put on
  /// the tool: the impulses Bullet's contact stage applied through the tool's holds
  /// (BulletSettings::holdInSolver), and the velocity changes of the nodes the last word moved,
  /// over the step. Most of a grasped body's weight reaches a jaw this way, not through wrench.
  /// Measured in a world whose soft-body solver is a thintool::SoftBodySolver; in the deformable
  /// world, with thintool::DeformableBodySolver, the impulses of Bullet's own rigid contacts on the
  /// tool and the last word's velocity changes; zero elsewhere.
  Wrench holdWrench;
  /// Force (N) and torque about the tool body's origin (N·m) of the impulses ThinTool applied to a
  /// dynamic tool in the step (the moved nodes' reactions, its holds' push after the soft solve,
  /// the pinned nodes' stops, and the force model's when it reacts on the tool), over the step:
  /// the tissue's load as the tool's motion took it. In the deformable world, with
  /// thintool::DeformableBodySolver, the momentum the last word's velocity changes gave the nodes
  /// and the pinned nodes' stops: Bullet's own contacts push the tool there, outside ThinTool.
  /// Zero for a static or kinematic tool, and in a world whose soft-body solver is neither.
  Wrench reaction;
  /// The tissue's force on the tool by the force model (Hunt–Crossley by default).
  ToolForce contactForce;
};

class CollisionConfiguration;
struct ToolModel;
namespace detail {
class SoftBodySolverImpl;
class ToolAlgorithm;
class SweptProxy;
struct ToolState;
}  // namespace detail

/// Created by addTool(); owned by the world's thintool::CollisionConfiguration.
class THINTOOL_API Tool {
 public:
  ~Tool();
  Tool(const Tool&) = delete;
  Tool& operator=(const Tool&) = delete;

  const std::string& name() const;
  btCollisionObject& body() const;
  /// The body as a btRigidBody, or null for a plain btCollisionObject (a static tool, or one the
  /// program moves).
  btRigidBody* rigidBody() const;
  /// The body when it is a dynamic btRigidBody, which takes the tissue's reaction; else null (a
  /// dynamic multibody link takes it too, through its multibody's joints).
  btRigidBody* dynamicBody() const;
  const ToolOptions& options() const;

  /// Convex pieces: one for a convex shape, one per child for a btCompoundShape.
  Index pieceCount() const;
  /// The piece's model (its planes, hull and sample nodes; declared in the core's tool/ToolModel.h,
  /// which the viewer and the evaluation suite read).
  const ToolModel& piece(Index i) const;
  /// A piece's frame in the body's frame (identity but for compound children).
  const Pose& pieceTransform(Index i) const;
  Index nodeCount() const;

  /// Contacts, diagnostics and wrench of the latest simulation step. Read it after
  /// stepSimulation() returns; the reference stays valid until the next call.
  const ToolStepReport& report();

  /// Takes the soft body's current shape as its rest shape for the force model's deformation. By
  /// default the rest shape is the one the body had when the force model first met it.
  void captureRestShape(const btSoftBody& softBody);

  /// Declares that the tool's next move is a jump (re-homing a device, a pose set by hand), not
  /// a motion: swept detection and the last word then do not sweep the space in between for one
  /// step. Nothing else is taken for a jump, however far the tool moves or turns in a step. A
  /// dynamic tool's jump ends where it is at the next step's collision pass: the motion Bullet
  /// integrates from there in that step is swept.
  void resetMotion();

 private:
  Tool(btCollisionObject& body, const ToolOptions& options, std::vector<ToolModel> pieces,
       std::vector<Pose> pieceTransforms);
  friend class detail::ToolAlgorithm;
  friend class detail::SweptProxy;
  friend class detail::SoftBodySolverImpl;
  friend class CollisionConfiguration;
  friend Tool& addTool(btCollisionWorld&, btCollisionObject&, const ToolOptions&);
  friend bool removeTool(btCollisionWorld&, const btCollisionObject&);
  detail::ToolState& state() const { return *m_state; }

  std::unique_ptr<detail::ToolState> m_state;
};

}  // namespace thintool
