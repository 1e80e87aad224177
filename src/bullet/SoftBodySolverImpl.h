// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// What thintool::SoftBodySolver does behind its public face (bullet/SoftBodySolver.h): Bullet's
// solve stage by stage for the bodies tools hold, the last word and the energy guard.

#include "geometry/Aabb.h"
#include "response/Separation.h"

#include <LinearMath/btAlignedObjectArray.h>
#include <LinearMath/btVector3.h>

#include <array>
#include <vector>

class btSoftBody;

namespace thintool {

class CollisionConfiguration;
class Tool;

namespace detail {

class DynamicBody;

// Mass, kinetic energy and momentum of a soft body's free nodes at some velocity of each.
struct BodyMotion {
  double mass = 0;
  double kinetic = 0;
  btVector3 momentum{0, 0, 0};
};

class SoftBodySolverImpl {
 public:
  /// softBodySet: the owning solver's soft bodies (btDefaultSoftBodySolver::m_softBodySet, or
  /// btDeformableBodySolver::m_softBodies when deformable).
  SoftBodySolverImpl(CollisionConfiguration& configuration, btAlignedObjectArray<btSoftBody*>& softBodySet,
                     bool deformable = false);

  // The classic solver's steps (SoftBodySolver).
  void solveConstraints(btScalar timeStep);
  void predictMotion(btScalar timeStep);

  /// Both solvers', at the start of a step of timeStep (s), before the collision pass: the
  /// impulses ThinTool applies to a dynamic tool are summed from here on (ToolStepReport::reaction).
  void beginToolSteps(btScalar timeStep);

  // Before Bullet's predictMotion: the fastest free node of each body (the deformable solver's), or
  // of each active pressure body only (the classic solver's energy guard).
  void rememberSpeeds(bool pressureBodiesOnly = false);
  // The deformable solver's (DeformableBodySolver): before Bullet's applyTransforms, where each
  // node begins the step; after it, the last word, with neither holds in a solve nor energy guard.
  void rememberStarts();
  void lastWordAfterTransforms();
  /// Before Bullet's solve: the node contacts of the tools that give their own in the deformable
  /// world (BulletSettings::deformableNodeContacts) replace Bullet's with them (DeformableBodySolver.cpp).
  void feedNodeContacts(btSoftBody& body);
  void feedToolNodeContacts(btSoftBody& body, Tool& tool);
  /// Adds to the hold wrench of the tool whose body is object, if any, an impulse Bullet's solve
  /// applied to it at point over a step of timeStep (s): the deformable world's contacts.
  void addSolverImpulse(const btCollisionObject& object, const btVector3& impulse, const btVector3& point,
                        btScalar timeStep);

 private:
  // The energy guard's measures of one soft body in this step (EnergyGuardSettings).
  struct BodyEnergy {
    double predicted = -1;  // kinetic energy about the centre of mass before the solve (J); < 0: not guarded
    double allowance = 0;   // ½·m·u² over the nodes ThinTool moved, u the tool's speed there (J)
    double toolAtMovedNodes = 0;  // the fastest tool point at a node ThinTool moved (m/s)
    double predictedFastest = 0;  // the fastest node as Bullet predicted it, before the solve (m/s)
    double toolFastest = 0;  // the guarding tools' fastest corner over the step (m/s)
    int piecesHolding = 0;   // tool pieces whose response moved or held a node of the body this step
    double speedFactor = 1;
    double energySlack = 0;
    double restingSpeed = 0;
    bool boundForcesNextStep = false;
    bool lastWordFollows = false;  // a guarding tool's last word runs after the solve
  };

  // In the deformable world, the guard's bound on the body's node speed (m/s), negative for none;
  // and, within it, the moves of Bullet's solve (moves: m_q holding each node's start) or, after
  // the last word, the velocities.
  double deformableSpeedBound(const btSoftBody& body, double startFastest) const;
  void boundDeformableSpeeds(btSoftBody& body, double allowed, bool moves);
  // Whether the last word keeps this body's nodes out of tools: the classic solver's bodies whose
  // pairs are ThinTool's or faceless (lastWordActsOn), and every body of the deformable solver.
  bool actsOn(const btSoftBody& body) const;
  // The step's last word in three parts: which tools speak and where their pieces reach; the
  // passes of every piece over the soft bodies; where the tools' next step starts.
  void beginLastWord();
  void separateEverything();
  void endLastWord();

  // Where the tool's motion over this step starts: where the last word left it, or where it is
  // now after a jump (Tool::resetMotion).
  static Pose stepStart(const Tool& tool, const Pose& now);
  // Before Bullet's solve: which soft bodies are guarded, their predicted energy and fastest node,
  // and what the collision pass's moves allow.
  void measureEnergy(btScalar timeStep);
  // After the last word: the guarded bodies' velocities brought within their bounds.
  void guardEnergy();
  // A pressure body's fastest node at the end of this step (SoftBodyCache::endFastest), where the
  // guard acted on it or, unguarded, where a guarding tool's pair with it is live.
  void recordPressureSpeeds(btSoftBody& softBody, bool guarded, double fastest);
  bool guardingToolNear(const btSoftBody& body) const;
  // Whether the tool's pair with the body is live this step.
  static bool hasLivePair(const Tool& tool, const btSoftBody& body);

  // What one pass of the last word does: its rounds (separateFromPiece), once the passes ran out
  // the last resort (carryMeetingFaces), and after it the nodes' last say (keepNodesOutside).
  enum class Stage { Rounds, LastResort, NodesLast };
  // One pass of the tool's pieces over the soft bodies; returns whether it moved anything.
  bool separate(Tool& tool, Stage stage);
  SeparationCounts separatePiece(Tool& tool, const ToolModel& piece, const PieceMotion& motion, btSoftBody& softBody,
                                 Stage stage, const std::vector<NearPiece>& near);
  // Fills m_nearPieces with the pieces of every tool whose reach meets that of the tool's piece p.
  void findNearPieces(const Tool& tool, Index p, const PieceMotion& motion);

  // What the gather keeps per soft body. The faces of each node (CSR), rebuilt when the body's
  // node or face count changes. And a bound on how far a face's box (its nodes at the start and
  // the end of the step) reaches from any of its nodes: a face whose box meets the piece's reach
  // has every node within that bound of it, so the gather looks at the faces of the nodes near
  // the reach grown by it, never at all the faces. The bound is measured exactly, then grown
  // each step by twice the farthest any node moved, and measured again once it has grown
  // kReachGrowth-fold.
  struct SoftBodyCache {
    const btSoftBody* softBody = nullptr;
    Index nodeCount = kInvalidIndex;
    Index faceCount = kInvalidIndex;
    Index linkCount = kInvalidIndex;
    const void* linkArray = nullptr;
    // Where the body's node and face arrays were: a body deleted and another made at the same
    // address, or arrays grown in place of others, are not taken for the same topology.
    const void* nodes = nullptr;
    const void* faceArray = nullptr;
    std::vector<Index> begin;
    std::vector<Index> faces;
    std::vector<std::array<Index, 3>> faceNodes;  // each face's nodes, read without Bullet's face records
    // Every edge of the faces is shared by exactly two of them: the surface bounds a volume, and
    // whether a tool piece lies inside it has an answer (the winding number).
    bool closed = false;
    // Every edge of the faces is a link that is not a bending one: the solve's preparation of the
    // links, which reads every link's length at the step's start anyway, then bounds the faces.
    bool edgesAreLinks = false;
    Real faceReach = 0;
    Real measuredReach = -1;  // at the last exact measure; negative: never measured
    int stepSeen = -1;
    // Every node at the start and the end of this step, when boundsHold (all of them finite).
    Aabb bounds;
    bool boundsHold = false;
    // The pinned nodes (zero inverse mass), listed in steps where a dynamic tool takes reactions.
    std::vector<Index> pinned;
    // The nodes the step's gathers can want, so that each gather looks at these, not at every
    // node: those whose move this step meets the step's reach grown by kReachGrowth times the
    // measured face reach (what faceReach can grow to before it is measured again), and those the
    // last word has moved since. Kept in the order of the body's nodes when a gather reads them.
    // Without a measure to grow from, or after one that outgrew it, candidatesHold is false and
    // the gathers look at every node.
    std::vector<Index> candidates;
    std::vector<unsigned char> isCandidate;  // per node
    bool candidatesHold = false;
    bool candidatesSorted = true;
    Real candidateReach = 0;  // the face reach the candidates cover
    // How much further a face reaches since the survey for the last word's moves in this step: the
    // face reach covers the solve's moves only.
    Real lastWordReach = 0;
    // The bound on what the body's forces add to a node's velocity in the step after boundStep
    // (EnergyGuardSettings::boundForcesNextStep), m/s per axis: the larger of speedFactor times
    // the fastest node, tool corner or restingSpeed, and, in a grasp, the body's extent over the step.
    double nextForceBound = 0;
    int boundStep = -1;
    // A pressure body's fastest node at the end of step speedStep, as the guard left it, and at the
    // end of the latest step the guard did not act in (m/s; negative: not measured). Bullet
    // applies the pressure in its prediction and the links take most of it back in the solve, so
    // the predicted speed of a light pressure body (60 to 200 m/s where it ends a step at 7) is no
    // measure of its own motion; these are.
    double endFastest = -1;
    double ownFastest = -1;
    int speedStep = -1;
    // Where the solve's last pass is ThinTool's and the energy guard bounds the body (motionSolved),
    // that pass leaves each node's shares of the guard's sums, zero for a pinned node: ½·m·v², m·v
    // and v², 28 bytes a node where Bullet's node is 256. After the last word the guard
    // recomputes the shares of the nodes it changed (changed, isChanged) and adds them all up in
    // the nodes' order, as its pass over the nodes would, to the same bits.
    std::vector<double> kineticShare;
    std::vector<btVector3> momentumShare;
    std::vector<btScalar> speedSquared;
    double solvedMass = 0;
    bool motionSolved = false;
    std::vector<Index> changed;
    std::vector<unsigned char> isChanged;
    // Bullet's pose-matching frame (btSoftBody::Pose::m_rot) at the latest prediction that found
    // one, or that keepPoseFrame made (a rotation either way); and the step it last repaired.
    btMatrix3x3 poseFrame = btMatrix3x3::getIdentity();
    int frameRepairStep = -1;
    Index frameNonFiniteWrites = 0;  // in that repair
  };
  // Bullet's pose matching with a frame that is a rotation (see the definition).
  void keepPoseFrame(btSoftBody& softBody, SoftBodyCache& cache);
  SoftBodyCache& cacheOf(const btSoftBody& softBody);
  SoftBodyCache* findCache(const btSoftBody& softBody);  // nullptr: none yet
  // The stage on the gathered patch, run again with the faces of the nodes it moved until none is
  // missing.
  SeparationCounts separateGrowingPatch(Tool& tool, const ToolModel& piece, const PieceMotion& motion,
                                        const btSoftBody& softBody, const SoftBodyCache& cache, Stage stage,
                                        const std::vector<NearPiece>& near);
  // A turning piece whose centre ends the step inside a closed body it was outside of at the start
  // is put back outside (see the definition).
  void keepOutsideClosedBody(Tool& tool, const ToolModel& piece, const PieceMotion& motion, const btSoftBody& softBody,
                             const SoftBodyCache& cache, const std::vector<NearPiece>& near,
                             SeparationCounts& counts);
  // The patch's vertex of a soft node, added with the node when absent; a soft face, added once.
  Index patchVertexOf(const btSoftBody& softBody, const SoftBodyCache& cache, Index node);
  void addPatchFace(const btSoftBody& softBody, const SoftBodyCache& cache, Index f);
  // The body's cache with its topology up to date, not yet surveyed in this step.
  SoftBodyCache& topologyOf(const btSoftBody& softBody);
  // Once a step, a pass over the body's nodes: the face reach, the box of the nodes and the
  // gathers' candidates. Run in the solve's last pass over the nodes where the solve is ThinTool's
  // (solveInStages), or on its own.
  struct NodeSurvey {
    btScalar farthest = 0;  // squared
    bool finite = true;
    btVector3 lowest{BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT};
    btVector3 highest{-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT};
    btVector3 wantedLow{0, 0, 0};  // where a node's move makes it a candidate
    btVector3 wantedHigh{0, 0, 0};
    bool collect = false;
  };
  NodeSurvey beginSurvey(SoftBodyCache& cache, int step);
  // pinned: the node is pinned and the step lists pinned nodes (m_dynamicToolsActive).
  void surveyNode(NodeSurvey& survey, SoftBodyCache& cache, int i, const btVector3& x, const btVector3& q, bool pinned);
  // longestStartEdge: the longest link that is not a bending one at the step's start (m), or
  // negative when the caller did not measure it.
  void finishSurvey(const NodeSurvey& survey, SoftBodyCache& cache, const btSoftBody& softBody,
                    Real longestStartEdge = -1);
  // The soft body's pinned nodes stop the dynamic tool that carries the piece short of them.
  void stopAtPinnedNodes(DynamicBody& tool, const ToolModel& piece, const Pose& pieceEnd, Real inverseStep,
                         const SoftBodyCache& cache, const btSoftBody& softBody, Index& nonFiniteWrites);
  // Coulomb's friction at the held nodes after a contact stage, as position-based dynamics has it
  // (Macklin et al. 2014, §6.1): the stage's push along the hold's normal bounds how far the node
  // is taken along with the tool's surface.
  void applyHoldFriction(btSoftBody& body, double inverseStepSquared);
  // A hold treats its tool as immovable within the solve; after it, a dynamic tool takes each held
  // node's push back as that node's reaction (ToolReaction.h: capped at an inelastic collision's
  // exchange, so that a needle light about its axis is not spun by its holds).
  void reactToHolds(btSoftBody& body);
  // The soft solve of each active body. A body that tools hold in the solver (their holds among
  // its contacts), that the last word will look at or that the energy guard bounds is solved by
  // solveInStages, the others by Bullet's own solveConstraints.
  void solveSoftBodies();
  // Whether a tool of this step's last word acts on the body.
  bool lastWordReaches(const btSoftBody& body) const;
  // Lists in m_held the nodes that tools hold in this body's solve; false when none.
  bool collectHolds(btSoftBody& body);
  // btSoftBody::solveConstraints, stage for stage, with each contact stage of the position solve
  // measured (the moves of the held nodes are the impulses their holds applied) and the last
  // word's survey in its last pass over the nodes.
  // longestMove (m): a guarded body's bound on each node's move over the step (fastestAllowed),
  // BT_LARGE_FLOAT for none.
  // guarded: the energy guard bounds the body; its shares are kept in the last pass.
  void solveInStages(btSoftBody& body, btScalar longestMove, bool guarded);
  // A guarded body's motion and its fastest free node's squared speed after the last word: from
  // the shares of the solve's last pass where it kept them, else from a pass over the nodes.
  BodyMotion motionAfterLastWord(const btSoftBody& softBody, btScalar& fastestSquared);
  // Node i's shares of the guard's sums at velocity v, with inverse mass im
  // (SoftBodyCache::kineticShare); returns its mass, zero for a pinned node.
  static double keepShares(SoftBodyCache& cache, int i, const btVector3& v, btScalar im);
  // Calls report with the last-word diagnostics of each tool with a live pair on the body.
  template <typename Report>
  void reportToToolsNear(const btSoftBody& body, const Report& report);
  // The energy guard's bound on a node's speed (EnergyGuardSettings), m/s.
  static double fastestAllowed(const BodyEnergy& energy);
  // Splits a contact stage's moves of the nodes that several tools held among those tools.
  void replaySharedHolds(btSoftBody& body, double inverseStepSquared);

  // Fills m_backingOfNode from the soft body's contacts of this step.
  void findBackings(const btSoftBody& softBody);

  // How far the face reach may grow before it is measured again, as a multiple of the last
  // measure (or bound): the measure visits every face, and the gather's work grows with the reach.
  static constexpr Real kReachGrowth = 2;
  static constexpr int kMostPasses = 4;
  // A pose-matching frame is a rotation when R·Rᵀ is the identity within this, entry by entry
  // (btPolarDecomposition's converged frames are within 1e-6, its failures off by thousands); the
  // rotation that replaces one that is not takes at most this many of Müller's iterations.
  static constexpr btScalar kFrameTolerance = btScalar(1e-2);
  static constexpr int kFrameIterations = 32;
  // A bound on one step's work only: the patch grows until no moved node has a face outside it,
  // one ring of faces an extension, and a patch that only grows ends by itself. A cascade of faces
  // pushed into a plate by their neighbours' moves took more than four extensions (generated
  // seed 70, a tetrahedral box under a plate turning 156° a step); one along a 0.6 m needle read
  // on its chord took 119, and a bound of 64 left faces across it (seed 5451).
  static constexpr int kMostExtensions = 1024;

  CollisionConfiguration& m_configuration;
  std::vector<Tool*> m_active;  // tools whose stage runs this step
  int m_piecesNear = 0;         // (piece, soft body) pairs with soft features near, this pass
  bool m_carried = false;       // this pass carried crossed faces with a piece (keepOutsideClosedBody)
  SeparationPatch m_patch;
  std::vector<NearPiece> m_nearPieces;  // the pieces near the one being separated
  std::vector<Index> m_vertexOfNode;  // soft node -> patch vertex, kInvalidIndex when absent
  std::vector<unsigned char> m_faceInPatch;  // soft face -> whether the patch has it
  std::vector<Index> m_patchFaces;           // the soft faces the patch has
  std::vector<SoftBodyCache> m_caches;
  std::vector<BodyEnergy> m_energy;  // one per soft body of the world, this step
  std::vector<Index> m_nearNodes;  // soft nodes near the piece's reach grown by the face reach
  // soft node -> during a gather, 0: not in m_nearNodes, 1: in it, 2: and its move meets the reach
  std::vector<unsigned char> m_isNearNode;
  // Every active tool's pieces, swept over this step and grown by their clearance; hasStepReach is
  // false until the step's tools are known.
  Aabb m_stepReach;
  bool m_hasStepReach = false;
  // soft node -> its contact in the soft body's m_rcontacts with a static or kinematic body, -1 for
  // none; filled only while a dynamic tool takes the reaction of moved nodes
  std::vector<int> m_backingOfNode;
  // A soft node that tools held in this step's solve: the first tool that held it, whether others
  // did too or a contact of Bullet's own holds it as well, and where it was before a contact stage.
  struct HeldNode {
    int node = 0;
    Tool* tool = nullptr;
    bool severalTools = false;
    bool bulletContact = false;
    btVector3 before{0, 0, 0};
    btVector3 replayed{0, 0, 0};
    btVector3 pushed{0, 0, 0};  // the holds' moves of the node over the solve, friction's included
    // Friction at the hold (PairState::holdSurfaceMoves), when its tool is dynamic and has friction
    // and its contact does not already stick: the hold's normal and the tool surface's move over
    // the step.
    btScalar staticFriction = 0;
    btScalar kineticFriction = 0;
    btVector3 normal{0, 0, 0};
    btVector3 surfaceMove{0, 0, 0};
  };
  // A hold on a node that several tools held: the contact stage's move of such a node is split
  // among them by replaying their holds one by one, in the stage's order.
  struct SharedHold {
    int contact = 0;
    int held = 0;  // entry in m_held
    Tool* tool = nullptr;
    btVector3 pushed{0, 0, 0};  // this tool's hold's moves of the node over the solve
  };
  std::vector<HeldNode> m_held;
  // This body's holds among its contacts (m_rcontacts indices), and whether one of their pairs
  // asks for the holds' last say in each position iteration (PairState::holdsLast).
  std::vector<int> m_holdContacts;
  bool m_holdsLast = false;
  // After each position iteration's stages: the holds alone, once more, as Bullet's contact stage
  // solves them.
  void solveHoldsLast(btSoftBody& body);
  std::vector<SharedHold> m_sharedHolds;
  // A hold whose tool limits how far along its plane it reaches (BulletSettings::holdPlaneReach):
  // before each contact stage its contact's normal is the plane's, or zero, which Bullet's contact
  // stage leaves idle, when the node put on the plane lies beyond the piece grown by reach.
  struct ReachingHold {
    int contact = 0;
    const ToolModel* piece = nullptr;
    Pose piecePose;
    Real reach = 0;  // m, past the piece's faces
    btVector3 normal{0, 0, 0};
  };
  std::vector<ReachingHold> m_reachingHolds;
  // Sets each reaching hold's contact normal for the next contact stage (see ReachingHold).
  void limitHoldReach(btSoftBody& body);
  std::vector<int> m_heldOfNode;  // soft node -> its entry in m_held, -1 for none
  int m_step = 0;
  bool m_dynamicToolsActive = false;  // a tool of this step's last word is dynamic and takes reactions
  btAlignedObjectArray<btSoftBody*>& m_softBodySet;
  bool m_deformable = false;
  // Deformable: per body of the set, each node where the step began, the fastest free node
  // then (m/s), and in the step's last word its speed bound (deformableSpeedBound: negative for
  // none), or kNotReached where the step's reach misses the body.
  std::vector<std::vector<btVector3>> m_starts;
  std::vector<double> m_startFastest;
  std::vector<double> m_speedBound;
  static constexpr double kNotReached = -2;
};

}  // namespace detail
}  // namespace thintool
