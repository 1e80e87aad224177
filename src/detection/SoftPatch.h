// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Plain-data views of a soft body that the core reads; the Bullet glue fills them.

#include <thintool/core/Math.h>

#include <array>
#include <vector>

namespace thintool {

/// The soft faces near one tool piece for one step, and the soft nodes they use.
/// Vertices are local to the patch; nodeIds and faceIds map back to the soft body.
struct SoftPatch {
  std::vector<Vec3> positions;          ///< world, end of step as predicted by the soft solver
  std::vector<Vec3> previousPositions;  ///< world, start of step
  /// World: where swept detection left each node at the end of its previous step, before the
  /// soft solver moved it to previousPositions; empty, or equal to previousPositions, when unknown.
  std::vector<Vec3> checkedPositions;
  std::vector<Real> inverseMasses;
  std::vector<Index> nodeIds;
  std::vector<std::array<Index, 3>> faces;  ///< local vertex indices
  std::vector<Index> faceIds;

  /// +1 when the soft body's faces wind counter-clockwise seen from outside, -1 when they wind the
  /// other way, 0 when the surface is open and has no outside (a sheet): check 2 is then skipped.
  int orientation = 1;

  void clear() {
    positions.clear();
    previousPositions.clear();
    checkedPositions.clear();
    inverseMasses.clear();
    nodeIds.clear();
    faces.clear();
    faceIds.clear();
  }
  Index vertexCount() const { return static_cast<Index>(positions.size()); }
  Index faceCount() const { return static_cast<Index>(faces.size()); }

  /// The arrays describe the same vertices and faces, and every face's vertices are in range: what
  /// the glue's gather guarantees the stages (checked by THINTOOL_ASSERT, core/Assert.h).
  bool consistent() const {
    const std::size_t n = positions.size();
    if (previousPositions.size() != n || inverseMasses.size() != n || nodeIds.size() != n ||
        !(checkedPositions.empty() || checkedPositions.size() == n) || faceIds.size() != faces.size()) {
      return false;
    }
    for (const std::array<Index, 3>& face : faces) {
      for (Index v : face) {
        if (v >= n) return false;
      }
    }
    return true;
  }
};

/// A query into the whole soft surface, beyond the patch: check 2's reverse ray must be able to
/// reach the far side of the soft body.
class SoftSurfaceRayQuery {
 public:
  virtual ~SoftSurfaceRayQuery() = default;
  /// Whether the segment from + t·delta, t in [0, 1], crosses a soft face.
  virtual bool anyHit(const Vec3& from, const Vec3& delta) const = 0;
};

}  // namespace thintool
