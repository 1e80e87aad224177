// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// What detection is told (the paper's filters) and what it finds (contacts and counters), as a
/// program sets and reads them; detection/Detection.h and detection/SweptDetection.h are the stages.

#include <thintool/core/Math.h>
#include <array>
#include <cstdint>
#include <optional>

namespace thintool {

/// The filters of §III.B, switchable per tool; a filter that is off costs nothing.
struct FilterSettings {
  /// Check 1, from the previous step's collisions across the tool. Needs association.
  bool check1 = true;
  /// Check 2, from the orientation of the soft face and a reverse ray.
  bool check2 = true;
  /// Check 2 also casts the reverse ray (a long ray; the orientation test alone is cheap).
  bool reverseRay = true;
  /// Length of the reverse ray (m, > 0); empty uses the soft body's bounding-box diagonal.
  std::optional<Real> reverseRayLength;
};

/// What met what.
enum class ContactKind : std::uint8_t {
  ToolRay,    ///< a tool node's ray met a soft face (the paper's contact; discrete detection)
  SoftNode,   ///< a soft node entered the tool (swept detection)
  ToolPoint,  ///< a point of the tool met a soft face (swept detection)
  Edge,       ///< an edge of the tool met an edge of the soft surface (swept detection)
};

/// One contact of a step: a soft point (a node, a point on an edge or on a face) and the plane
/// it must end the step on the positive side of: dot(normal, point) + offset >= 0, the tool's
/// surface moved out by the skin, on the side the soft point came from.
struct Contact {
  ContactKind kind = ContactKind::ToolRay;
  Index toolNode = kInvalidIndex;     ///< ToolRay, ToolPoint: the tool's sample node; else kInvalidIndex
  Index toolFeature = kInvalidIndex;  ///< SoftNode: the face entered; ToolPoint: the hull vertex, if not a node; Edge: the tool edge
  Index softFace = kInvalidIndex;     ///< ToolRay, ToolPoint: the soft face, in the soft body
  std::array<Index, 3> softNodes{kInvalidIndex, kInvalidIndex, kInvalidIndex};  ///< in the soft body
  Index softNodeCount = 0;            ///< 3 for a face, 2 for an edge, 1 for a node
  Vec3 barycentric;    ///< weights of softNodes at the contact point
  Real depth = 0;      ///< how far the soft point lies past the tool's surface (m); negative: in the skin only
  Vec3 normal;         ///< world, unit, out of the tool on the side the soft point came from
  Vec3 point;          ///< world, the soft point
  Real offset = 0;     ///< plane offset (m), see above
  Real timeOfImpact = 1;  ///< fraction of the step when the features met (1: at its end)
};

struct DetectionCounters {
  Index facesGathered = 0;   ///< soft faces in the patch
  /// Soft faces the glue listed as the patch's candidates, by its walk of the soft body's face tree
  /// or its scan of the faces' motion (0 when the patch came from elsewhere).
  Index facesWalked = 0;
  Index nodesTested = 0;     ///< tool nodes whose ray was tested against at least one face
  Index triangleTests = 0;   ///< segment–triangle tests run
  Index candidates = 0;      ///< nodes whose ray found a face
  Index colliding = 0;
  Index excludedByCheck1 = 0;
  Index excludedByCheck2 = 0;
  /// Faces left out: with non-finite coordinates, or (swept detection) of zero area near the tool.
  Index skippedFaces = 0;
  Real maxDepth = 0;         ///< deepest accepted contact (m), 0 without contacts

  void accumulate(const DetectionCounters& o);
};

}  // namespace thintool
