// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/AabbTree.h"

#include <algorithm>

namespace thintool {

void AabbTree::build(const std::vector<Aabb>& itemBoxes) {
  m_nodes.clear();
  m_leafBoxes.clear();
  m_items.resize(itemBoxes.size());
  if (itemBoxes.empty()) {
    return;
  }
  std::vector<Vec3> centres(itemBoxes.size());
  for (Index i = 0; i < itemBoxes.size(); ++i) {
    m_items[i] = i;
    centres[i] = itemBoxes[i].center();
  }
  // A binary tree with leaves of >= 1 item has fewer than 2·items nodes.
  m_nodes.reserve(2 * itemBoxes.size());
  m_nodes.emplace_back();
  buildRange(itemBoxes, centres, 0, static_cast<Index>(itemBoxes.size()), 0);
  m_leafBoxes.resize(m_items.size());
  for (Index k = 0; k < m_items.size(); ++k) {
    m_leafBoxes[k] = itemBoxes[m_items[k]];
  }
}

void AabbTree::buildRange(const std::vector<Aabb>& itemBoxes, const std::vector<Vec3>& centres, Index begin,
                          Index end, Index nodeIndex) {
  Aabb box;
  Aabb centreBox;
  for (Index k = begin; k < end; ++k) {
    box.include(itemBoxes[m_items[k]]);
    centreBox.include(centres[m_items[k]]);
  }
  m_nodes[nodeIndex].box = box;
  if (end - begin <= kMaxLeafItems) {
    m_nodes[nodeIndex].first = begin;
    m_nodes[nodeIndex].count = end - begin;
    return;
  }

  const Vec3 spread = centreBox.extent();
  int axis = 0;
  if (spread.y > spread[axis]) axis = 1;
  if (spread.z > spread[axis]) axis = 2;
  const Index middle = begin + (end - begin) / 2;
  std::nth_element(m_items.begin() + begin, m_items.begin() + middle, m_items.begin() + end,
                   [&centres, axis](Index a, Index b) { return centres[a][axis] < centres[b][axis]; });

  const Index left = static_cast<Index>(m_nodes.size());
  m_nodes.emplace_back();
  m_nodes.emplace_back();
  m_nodes[nodeIndex].first = left;
  m_nodes[nodeIndex].count = 0;
  buildRange(itemBoxes, centres, begin, middle, left);
  buildRange(itemBoxes, centres, middle, end, left + 1);
}

}  // namespace thintool
