// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// A static bounding-volume hierarchy over boxes, built once and queried many times.
///
/// Built top-down by median split of the item centres along the longest axis (Ericson,
/// "Real-Time Collision Detection", §6.2), which bounds the depth by log2(items) + 1, so queries
/// walk it with a fixed-size stack and never allocate. ThinTool builds one per tool over its ray
/// segments and one over its node patches; both live in the tool's own frame, so a moving tool
/// never refits them.

#include "geometry/Aabb.h"

#include <vector>

namespace thintool {

class AabbTree {
 public:
  /// Items per leaf. Four keeps the leaf's box tight around short ray segments.
  static constexpr Index kMaxLeafItems = 4;

  /// Builds over itemBoxes; item i of a query is itemBoxes[i]. An empty list gives an empty tree.
  void build(const std::vector<Aabb>& itemBoxes);

  bool empty() const { return m_nodes.empty(); }
  Index itemCount() const { return static_cast<Index>(m_items.size()); }
  const Aabb& bounds() const { return m_nodes.front().box; }

  /// Calls visit(item) for every item whose box overlaps box.
  template <class Visitor>
  void queryOverlap(const Aabb& box, Visitor&& visit) const {
    traverse([&box](const Aabb& nodeBox) { return nodeBox.overlaps(box); }, visit);
  }

  /// Calls visit(item) for every item whose box the segment touches.
  template <class Visitor>
  void querySegment(const SegmentSlab& segment, Visitor&& visit) const {
    traverse([&segment](const Aabb& nodeBox) { return segment.overlaps(nodeBox); }, visit);
  }

 private:
  struct Node {
    Aabb box;
    Index first = 0;  ///< inner node: left child (right is first + 1); leaf: first entry in m_items
    Index count = 0;  ///< 0 for an inner node, else the leaf's item count
  };

  static constexpr int kStackSize = 64;  // median split: depth <= log2(2^32) + 1

  template <class Test, class Visitor>
  void traverse(const Test& test, Visitor& visit) const {
    if (m_nodes.empty()) {
      return;
    }
    Index stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = m_nodes[stack[--top]];
      if (!test(node.box)) {
        continue;
      }
      if (node.count > 0) {
        for (Index k = node.first; k < node.first + node.count; ++k) {
          if (test(m_leafBoxes[k])) {
            visit(m_items[k]);
          }
        }
      } else {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

  void buildRange(const std::vector<Aabb>& itemBoxes, const std::vector<Vec3>& centres, Index begin, Index end,
                   Index nodeIndex);

  std::vector<Node> m_nodes;
  std::vector<Index> m_items;
  std::vector<Aabb> m_leafBoxes;  ///< item boxes in m_items order, for the test inside leaves
};

}  // namespace thintool
