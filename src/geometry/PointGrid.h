// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A uniform grid over a fixed set of points, built once and queried with boxes many times.
///
/// Swept detection asks, for each soft face near a tool, which of the tool's points lie in a small
/// box around the face. A bounding-volume tree answers by descending from its root each time; a
/// grid goes straight to the few cells under the box, which for boxes about one point spacing wide
/// costs a handful of cell reads instead of dozens of node tests. The cells are cubes sized so that
/// there are about as many cells as points whatever the set's shape (a flat plate gets one layer, a
/// needle one row), and each cell's points are stored together (compressed rows), so a query reads
/// memory in order and never allocates.

#include "geometry/Aabb.h"

#include <vector>

namespace thintool {

class PointGrid {
 public:
  /// Builds over points; item i of a query is points[i]. Points must be finite.
  void build(const std::vector<Vec3>& points);

  bool empty() const { return m_items.empty(); }
  Index cellCount() const { return static_cast<Index>(m_cellStart.empty() ? 0 : m_cellStart.size() - 1); }

  /// Calls visit(item, point) for every point inside box (boundary included): point is the grid's
  /// copy of points[item], read in cell order, so a caller need not look it up again.
  template <class Visitor>
  void queryBox(const Aabb& box, Visitor&& visit) const {
    if (m_items.empty() || !box.overlaps(m_bounds)) {
      return;
    }
    int low[3];
    int high[3];
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = cellOf(box.min[axis], axis);
      high[axis] = cellOf(box.max[axis], axis);
    }
    for (int z = low[2]; z <= high[2]; ++z) {
      for (int y = low[1]; y <= high[1]; ++y) {
        const Index row = static_cast<Index>((z * m_cells[1] + y) * m_cells[0]);
        const Index begin = m_cellStart[row + static_cast<Index>(low[0])];
        const Index end = m_cellStart[row + static_cast<Index>(high[0]) + 1];
        for (Index k = begin; k < end; ++k) {
          if (box.contains(m_points[k])) {
            visit(m_items[k], m_points[k]);
          }
        }
      }
    }
  }

 private:
  // The cell along axis that holds coordinate, clamped to the grid.
  int cellOf(Real coordinate, int axis) const {
    const Real cell = (coordinate - m_bounds.min[axis]) * m_inverseCellSize;
    if (!(cell > 0)) return 0;
    if (cell >= Real(m_cells[axis] - 1)) return m_cells[axis] - 1;
    return static_cast<int>(cell);
  }

  Aabb m_bounds;
  Real m_inverseCellSize = 1;
  int m_cells[3] = {1, 1, 1};
  std::vector<Index> m_cellStart;  ///< cell c holds entries m_cellStart[c] .. m_cellStart[c + 1] - 1
  std::vector<Vec3> m_points;      ///< the points in cell order
  std::vector<Index> m_items;      ///< their indices in the built set
};

}  // namespace thintool
