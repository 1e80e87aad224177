// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// How a tool piece is sampled and its nodes paired (tool/ToolModel.h builds the model from them).

#include <thintool/core/Math.h>
#include <optional>

namespace thintool {

enum class SamplingLayout {
  FacePatches,            ///< every face cut into cells of at most `spacing`; a node per cell
  HullTriangleCentroids,  ///< paper §III.C as written: a node per hull triangle; spacing unused
  BoxFaceGrid,            ///< ref. [3]: a grid on the two largest faces of a box; box pieces only
};

struct SamplingSettings {
  SamplingLayout layout = SamplingLayout::FacePatches;
  /// Cell size of the sampling grid (m, > 0). Empty picks 1/8 of the piece's largest extent:
  /// 0.1 m for the paper's 0.8 m plate, 160 nodes. Every soft face whose inscribed circle has a
  /// radius of at least spacing/√2 contains a node's ray; smaller faces can slip between the rays.
  std::optional<Real> spacing;
  /// Registration fails rather than build more nodes than this (a spacing typed in the wrong unit).
  Index maxNodes = 50000;
};

struct AssociationSettings {
  /// Pair nodes across the piece. Check 1 needs it; off, no pairs are built and check 1 is off.
  bool enabled = true;
  /// Longest association ray (m, > 0). Empty picks 1.5 × the piece's thickness, which pairs the
  /// faces across a thin direction and leaves nodes on the narrow sides unpaired (paper Fig. 6).
  std::optional<Real> maxRayLength;
};

struct ToolModelSettings {
  SamplingSettings sampling;
  AssociationSettings association;
  /// Deepest a soft face is looked for below a node (m, > 0); empty picks the piece's thickness.
  std::optional<Real> probeDepth;
};

}  // namespace thintool
