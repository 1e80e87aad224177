// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The force the soft tissue puts on a tool, for haptic feedback and for a dynamic tool's reaction.
///
/// Source: the paper's eq. (3), Hunt & Crossley (1975), F = k·xⁿ + λ·xⁿ·ẋ for x >= 0, else 0,
/// summed over the soft faces in contact; a face is in contact when one of its nodes collides
/// (the paper, §III.D). Two measures of the deformation x of a face are offered:
/// - DeformationMeasure::CentroidDisplacement, the paper's: the distance of the face's centroid
///   from where it was at rest. It counts the body's own rigid motion (a ball rolling away from
///   its rest pose) as deformation.
/// Either way a face's force pushes the tool back along the contact normal.
/// - DeformationMeasure::Indentation (default): how far the face's centroid has been pushed in
///   along the contact normal, measured from its rest position carried along by the body's rigid
///   motion. The rigid motion is estimated by shape matching (Müller et al., "Meshless
///   deformations based on shape matching", 2005) over a fixed set of nodes spread over the body,
///   its rotation extracted as in Müller et al., "A robust method to extract the rotational part
///   of deformations" (2016).
/// Deviations, each against a pitfall of the model: the force is clamped at 0, so a fast
/// withdrawal (ẋ < −k/λ) never pulls the tool back into the tissue; ẋ is the deformation's own
/// rate, low-pass filtered at ForceSettings::rateCutoff, and the damping term uses the same xⁿ as
/// the spring, so the force is 0 at first touch whatever the speed. The force does not act on
/// the soft body: the response (response/Response.h) already puts the nodes where the tool
/// allows, and a second tissue spring on top would count the tissue twice.

#include "core/StepStamps.h"
#include "detection/Detection.h"
#include "detection/SoftPatch.h"
#include "tool/StepContext.h"
#include "tool/ToolModel.h"

#include <thintool/core/Math.h>
#include <thintool/force/ForceTypes.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace thintool {

/// Hunt–Crossley's law, clamped at 0; 0 for x <= 0 and for non-finite input.
Real huntCrossleyForce(const HuntCrossley& model, Real deformation, Real rate);

/// A soft body's rest shape, and the nodes its rigid motion is estimated from.
class RestShape {
 public:
  /// Records positions (world) as the rest shape; up to anchorCount nodes spread over the body
  /// (by index stride) carry the rigid-motion estimate. inverseMasses weigh it; pinned nodes
  /// (inverse mass 0) weigh as the heaviest movable node.
  void capture(const std::vector<Vec3>& positions, const std::vector<Real>& inverseMasses, Index anchorCount = 256);
  bool empty() const { return m_positions.empty(); }
  Index nodeCount() const { return static_cast<Index>(m_positions.size()); }
  const Vec3& position(Index node) const { return m_positions[node]; }
  const std::vector<Index>& anchors() const { return m_anchors; }
  const std::vector<Real>& anchorWeights() const { return m_anchorWeights; }
  const Vec3& anchorCentroid() const { return m_anchorCentroid; }

 private:
  std::vector<Vec3> m_positions;
  std::vector<Index> m_anchors;
  std::vector<Real> m_anchorWeights;
  Vec3 m_anchorCentroid;
};

/// The rigid motion that best carries the rest anchors to their current positions (a least-squares
/// fit in the weights): current ≈ rotation·(rest − restCentroid) + centroid.
struct RigidFit {
  Mat3 rotation;  // identity
  Vec3 restCentroid;
  Vec3 centroid;
  Vec3 apply(const Vec3& rest) const { return rotation * (rest - restCentroid) + centroid; }
};

/// Fits the rigid motion from the anchors' current positions (anchorPositions[i] is where node
/// rest.anchors()[i] is now). previous seeds the rotation's iteration (the last step's fit).
RigidFit fitRigidMotion(const RestShape& rest, const std::vector<Vec3>& anchorPositions, const RigidFit& previous);

struct ForceInput;
struct ForceResult;

/// What the force model keeps per (tool piece, soft body) from one step to the next: each face's
/// last deformation and filtered rate, for ẋ.
class ForceHistory {
 public:
  void resize(Index faceCount);
  void reset();

 private:
  friend void computeContactForces(const StepContext&, const SoftPatch&, const std::vector<PatchContact>&, const ForceInput&,
                                   ForceResult&);
  std::vector<Real> m_lastDeformation;
  std::vector<Real> m_rate;
  StepStamps m_inContact;  ///< the faces in contact in a step, as each step leaves them
  std::vector<Vec3> m_vertexNormal;  ///< per patch vertex, scratch: sum of its contacts' normals
};

/// What the force model reads besides the step and its contacts.
struct ForceInput {
  const ForceSettings& settings;
  const RestShape& rest;      ///< the soft body at rest
  const RigidFit& rigidFit;   ///< the body's rigid motion now; ignored by the centroid measure
};

/// The forces of a step, and what the model carries to the next.
struct ForceResult {
  std::vector<FaceForce> faces;  ///< on the tool, one per soft face in contact
  ForceHistory history;          ///< resize it to the soft body's face count before a step
};

/// The forces of this step's soft faces in contact with the tool piece at the context's pose
/// (grown by its skin), on the tool. patch.positions must hold where the response left the nodes;
/// contacts' patchVertices index into patch. Allocates nothing once the result has grown to the
/// soft body.
void computeContactForces(const StepContext& step, const SoftPatch& patch, const std::vector<PatchContact>& contacts,
                          const ForceInput& input, ForceResult& out);

}  // namespace thintool
