// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// From a Bullet collision shape to the convex meshes the tool model is built from.

#include "geometry/ConvexMesh.h"

#include <thintool/core/Math.h>

#include <vector>

class btCollisionShape;
class btVector3;

namespace thintool::detail {

struct ShapePiece {
  ConvexMesh mesh;
  Pose transform;  ///< the piece's frame in the body's frame
};

/// One piece for a convex shape, one per child of a btCompoundShape. Throws thintool::Error for
/// shapes that are not convex, or compound children that are not.
///
/// Margins: a btBoxShape is its half extents (its margin is inside them); a polyhedral shape is
/// its points, without Bullet's collision margin, which would thicken a 2 mm blade by 8 cm at the
/// default 0.04; a round shape (sphere, capsule, cylinder, cone) is the hull of 162 support
/// points, margin included, since its margin is part of its size.
std::vector<ShapePiece> shapePieces(const btCollisionShape& shape);

/// The convex hull of points as a closed, outward-wound triangle mesh (Bullet's
/// btConvexHullComputer, then a fan per polygonal face). Empty when the points span no volume.
ConvexMesh hullOf(const std::vector<btVector3>& points);

}  // namespace thintool::detail
