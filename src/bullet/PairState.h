// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// What a tool keeps per (piece, soft body) pair. It lives with the tool, not in Bullet's per-pair
// algorithm objects: Bullet frees those when a pair separates and creates them anew when it
// returns, and the pair's algorithm only tells the state when that happens.

#include "core/StepStamps.h"
#include "detection/Detection.h"
#include "detection/SweptDetection.h"
#include "force/ContactForce.h"
#include "response/Response.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

class btRigidBody;
class btSoftBody;
struct btDbvtNode;

namespace thintool::detail {

/// The bodies a pair's holds refer to carry this address as their user pointer, which no body of
/// the user's can: the soft solver tells the holds from Bullet's own contacts by it.
inline constexpr char kHoldBodyMark = 0;

/// Why a tool's pair with a soft body is left to Bullet's stock handler (ToolDiagnostics::stockPairs).
enum class StockReason : std::uint8_t { None, DeformableWorld, ClusterCollision, NoRigidContact, NoFaces };

struct PairState {
  PairState();
  ~PairState();

  btSoftBody* softBody = nullptr;
  Index piece = 0;

  /// The pair's algorithm exists and has processed at least one step since it was created.
  bool live = false;

  PairHistory history;
  SideMemory sides;
  /// Largest soft node displacement seen in the pair's last step (m): how far beyond the tool's
  /// swept box to look for soft faces that may cross it.
  Real softReach = 0;
  /// Bounds of the soft body's node tree when the pair was last processed: how far they move in a
  /// step bounds the motion of a soft body arriving fast from afar, whose nodes near the tool had
  /// not been seen moving.
  Aabb softBounds;
  bool hasSoftBounds = false;
  /// Where swept detection left each soft node at the end of its last step (world), stamped with
  /// the sweep that left it there: the next sweep starts there rather than at Bullet's start of
  /// step, so that the soft solver's own moves in between (links, pressure) are swept too.
  std::vector<Vec3> lastPositions;
  StepStamps sweptNodes;
  SoftPatch patch;
  std::vector<Index> patchVertexOfNode;  ///< soft node -> patch vertex, kInvalidIndex when absent
  std::vector<const btDbvtNode*> traversalStack;
  std::vector<Index> candidateFaces;  ///< faces the gather listed
  std::vector<std::array<Index, 3>> faceCorners;  ///< each soft face's node indices, for the scan
  /// Face count the topology facts below were computed for.
  int facesSeen = -1;
  /// The skin the pair keeps (m): ToolOptions::skin, or less while it grows after a first step
  /// that found soft nodes inside it (ToolOptions::skinGrowthSpeed). Negative before that step.
  Real skinInEffect = -1;
  /// The piece's pose when the pair was last processed: the start of this step.
  Pose previousPose;
  bool hasPreviousPose = false;
  /// The force model's memory: each face's deformation rate, and the soft body's rigid motion.
  ForceResult force;  ///< the faces' forces, and their history for the rate
  RigidFit rigidFit;
  std::vector<Vec3> anchorPositions;
  /// Bodies that the solver contacts holding moved nodes refer to, one per node (see ToolAlgorithm).
  std::vector<std::unique_ptr<btRigidBody>> holdBodies;
  /// This step's holds: the soft body's m_rcontacts from firstHold on, holdCount of them, the k-th
  /// referring to holdBodies[k] (the soft solver checks that before it reads them).
  int firstHold = 0;
  int holdCount = 0;
  /// With friction, under thintool::SoftBodySolver: the soft body's holds get a contact stage of
  /// their own after the links in each position iteration of its solve (solveHoldsLast).
  bool holdsLast = false;
  /// With friction, for a dynamic tool: the tool surface's displacement over the step at each
  /// hold's node (world), and the pair's coefficients, for the soft solver's friction at the holds.
  /// Empty otherwise.
  std::vector<Vec3> holdSurfaceMoves;
  Real holdStaticFriction = 0;
  Real holdKineticFriction = 0;

  // Results of the latest step.
  DetectionResult detection;  ///< the contacts, counters and excluded nodes, with detection's scratch
  ResponseResult response;  ///< the corrections and the wrench, with the response's scratch
  std::vector<NodeHold> holds;
  double detectionMicroseconds = 0;
  double responseMicroseconds = 0;
  StockReason stock = StockReason::None;
  /// In the deformable world (BulletSettings::deformableNodeContacts): this step's node contacts
  /// go into Bullet's solve (thintool::DeformableBodySolver::setConstraints), and the patch's ends
  /// are the nodes' predicted places, which Bullet keeps in m_q there.
  bool feedsDeformable = false;
  bool invalidPose = false;
  Index nonFiniteWrites = 0;  ///< writes into Bullet's state left not finite (WriteCheck.h)
  /// The piece's pose where it stops a dynamic tool short of the patch's pinned nodes this step;
  /// stopsAtPinned is false when it stops it at none (ToolAlgorithm::stopAtPinnedNodes).
  Pose pinnedStopPose;
  bool stopsAtPinned = false;

  void clearResults() {
    detection.contacts.clear();
    detection.excludedNodes[0].clear();
    detection.excludedNodes[1].clear();
    detection.counters = DetectionCounters{};
    response.corrections.clear();
    response.wrench = Wrench{};
    holds.clear();
    force.faces.clear();
    holdCount = 0;
    holdsLast = false;
    detectionMicroseconds = 0;
    responseMicroseconds = 0;
    feedsDeformable = false;
    stock = StockReason::None;
    invalidPose = false;
    nonFiniteWrites = 0;
    stopsAtPinned = false;
  }

  /// The broadphase pair is gone: nothing of the last step carries over to the next contact.
  void separate() {
    clearResults();
    history.reset();
    sides.forget();
    force.history.reset();
    sweptNodes.forget();
    hasPreviousPose = false;
    skinInEffect = -1;
    hasSoftBounds = false;
    live = false;
  }
};

}  // namespace thintool::detail
