// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/PointGrid.h"

#include <algorithm>
#include <cmath>

namespace thintool {

namespace {

// The cube's edge that gives about `target` cells over extent, leaving out the axes thinner than
// a cell (they get one): solved over the axes kept, thinnest dropped first.
Real cellSizeFor(const Vec3& extent, Real target) {
  Real sorted[3] = {extent.x, extent.y, extent.z};
  std::sort(sorted, sorted + 3);
  for (int dropped = 0; dropped < 3; ++dropped) {
    const int kept = 3 - dropped;
    Real product = 1;
    for (int k = dropped; k < 3; ++k) product *= sorted[k];
    const Real size = std::pow(product / target, Real(1) / kept);
    if (size > 0 && sorted[dropped] >= size) {
      return size;
    }
  }
  return 1;  // every point at one place
}

}  // namespace

void PointGrid::build(const std::vector<Vec3>& points) {
  m_cellStart.clear();
  m_points.clear();
  m_items.clear();
  m_bounds = Aabb{};
  if (points.empty()) {
    return;
  }
  for (const Vec3& p : points) {
    m_bounds.include(p);
  }
  const Vec3 extent = m_bounds.extent();
  const Real cellSize = cellSizeFor(extent, Real(points.size()));
  m_inverseCellSize = 1 / cellSize;
  // At most a few cells per point along any axis, whatever the rounding above did.
  const Real most = std::max<Real>(1, 4 * Real(points.size()));
  for (int axis = 0; axis < 3; ++axis) {
    m_cells[axis] = static_cast<int>(std::clamp<Real>(std::floor(extent[axis] * m_inverseCellSize) + 1, 1, most));
  }
  while (Real(m_cells[0]) * m_cells[1] * m_cells[2] > 8 * most) {
    m_inverseCellSize *= Real(0.5);
    for (int axis = 0; axis < 3; ++axis) {
      m_cells[axis] = static_cast<int>(std::floor(extent[axis] * m_inverseCellSize) + 1);
    }
  }

  const Index cellTotal = static_cast<Index>(m_cells[0] * m_cells[1] * m_cells[2]);
  std::vector<Index> cellOfPoint(points.size());
  m_cellStart.assign(cellTotal + 1, 0);
  for (Index i = 0; i < points.size(); ++i) {
    const Index cell = static_cast<Index>(
        (cellOf(points[i].z, 2) * m_cells[1] + cellOf(points[i].y, 1)) * m_cells[0] + cellOf(points[i].x, 0));
    cellOfPoint[i] = cell;
    ++m_cellStart[cell + 1];
  }
  for (Index c = 0; c < cellTotal; ++c) {
    m_cellStart[c + 1] += m_cellStart[c];
  }
  m_points.resize(points.size());
  m_items.resize(points.size());
  std::vector<Index> next(m_cellStart.begin(), m_cellStart.end() - 1);
  for (Index i = 0; i < points.size(); ++i) {
    const Index slot = next[cellOfPoint[i]]++;
    m_points[slot] = points[i];
    m_items[slot] = i;
  }
}

}  // namespace thintool
