// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Per-step detection between one tool piece and the soft faces near it.
///
/// Source: Fazioli et al. (the paper) §III.B, after Fukuhara et al. (2014), and the inward-ray
/// rule of Hermann, Faure & Raffin, "Ray-traced collision detection for deformable bodies" (2008).
/// Each tool node casts a segment along its inward normal, from the skin (the soft body's contact
/// margin) in front of its face down to its probe length inside the piece. The closest soft face
/// the segment meets is the node's candidate; its depth t is how far that face lies inside the
/// tool's surface. Two filters, using the previous step, drop unfeasible candidates:
/// - check 1: a node one of whose opposite nodes collided in the previous step is excluded when
///   its ray finds a face (the piece is immersed and the face came in from the other side);
/// - check 2: the candidate face must face the node (the dot product of the tool face's and the
///   soft face's outward normals is negative, so the node lies behind that face, inside the soft
///   body) and the reverse ray, cast outwards from the node, must hit the soft surface as well.
/// Deviations: the paper does not say which normals check 2 compares or how long its rays are;
/// we compare the two faces in contact and bound the forward ray by the piece's width, which is
/// what makes a thin piece's two sides see the same soft face only when the face is inside it.
/// Soft faces are visited once each, and only the rays whose boxes they overlap are tested
/// (ToolModel::rayTree), so the cost follows the contact region, not the soft body's size.

#include "detection/SoftPatch.h"
#include "tool/StepContext.h"
#include "tool/ToolModel.h"

#include <thintool/detection/DetectionTypes.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace thintool {

/// The detection stage's input beyond the step and the patch: its settings, resolved by the glue
/// for one soft body (as ForceInput is for the force stage).
struct DetectionInput {
  FilterSettings filters;
  Real reverseRayLength = 0;  ///< filters.reverseRayLength, or the glue's choice when it is empty (m, > 0)
  /// The soft surface check 2's reverse ray is cast against; null when filters.reverseRay is off.
  const SoftSurfaceRayQuery* reverseQuery = nullptr;
};

/// A contact as the stages pass it on: its soft points also as indices into the step's SoftPatch.
/// The report gives the Contact alone.
struct PatchContact : Contact {
  std::array<Index, 3> patchVertices{kInvalidIndex, kInvalidIndex, kInvalidIndex};
  Index patchFace = kInvalidIndex;
};

/// What one (tool piece, soft body) pair carries from one step to the next: the nodes check 1
/// blocks, i.e. the opposites of the nodes that collided (the paper's "vector of indices that
/// cannot collide in the current simulation step").
class PairHistory {
 public:
  void reset();
  bool isBlocked(Index node) const { return node < m_blocked.size() && m_blocked[node] != 0; }
  Index blockedCount() const { return static_cast<Index>(m_blockedList.size()); }
  /// Records this step's colliding nodes for the next step.
  void record(const ToolModel& model, const std::vector<PatchContact>& contacts);

 private:
  std::vector<std::uint8_t> m_blocked;
  std::vector<Index> m_blockedList;
};

struct DetectionResult;

/// The ray detection's scratch, sized to the tool piece on first use and kept from step to step.
class DetectionWorkspace {
 public:
  void prepare(Index nodeCount);

 private:
  friend void detectContacts(const StepContext&, const SoftPatch&, const DetectionInput&, PairHistory&,
                             DetectionResult&);
  std::vector<Vec3> m_localPositions;
  std::vector<std::uint8_t> m_localValid;
  std::vector<Real> m_bestDistance;
  std::vector<Index> m_bestFace;
  std::vector<Real> m_bestU;
  std::vector<Real> m_bestV;
  std::vector<std::uint8_t> m_visited;
  std::vector<Index> m_visitedList;
};

/// What detection found in a step, and the scratch it found it with.
struct DetectionResult {
  std::vector<PatchContact> contacts;
  DetectionCounters counters;
  /// The tool nodes the ray detection excluded by check 1 and by check 2 (the viewer colours them).
  std::vector<Index> excludedNodes[2];
  DetectionWorkspace workspace;
};

/// Finds this step's contacts between the tool piece at the context's pose, grown by its skin, and
/// the soft patch, filters them, and updates the pair's history. Allocates nothing once the result
/// has grown to the patch and tool sizes.
void detectContacts(const StepContext& step, const SoftPatch& patch, const DetectionInput& input,
                    PairHistory& history, DetectionResult& out);

}  // namespace thintool
