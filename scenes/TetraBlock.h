// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A rectangular block of tetrahedra as a classic btSoftBody: a soft cube, or a cable when one side
/// is much longer than the others.

#include <thintool/core/Math.h>

#include <array>

class btSoftBody;
struct btSoftBodyWorldInfo;

namespace thintool::scenes {

/// A block centred at centre (m) of the given size (m along x, y, z), cells[a] cells along axis a,
/// each cell cut into six tetrahedra round its main diagonal (Kuhn's subdivision: every cell cut
/// the same way, so neighbours share their faces' diagonals). Built through TetGen's .node and .ele
/// text, which btSoftBodyHelpers::CreateFromTetGenData reads with links along the tetrahedra's
/// edges; it ignores faces, so the surface (the faces of one tetrahedron only, wound outward, as
/// the pressure wants them) is appended with their links. Throws thintool::Error for a count
/// below 1. The caller owns the body.
btSoftBody* createTetraBlock(btSoftBodyWorldInfo& info, const Vec3& centre, const Vec3& size,
                             const std::array<int, 3>& cells);

}  // namespace thintool::scenes
