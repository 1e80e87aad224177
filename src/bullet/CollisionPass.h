// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// What ThinTool did to soft bodies during the current collision pass that their face trees do not
// know. Bullet refits each face tree leaf around its face grown by the soft margin in
// btSoftBody::predictMotion, just before the pass; a walk of the tree may then shrink its box by
// that margin, less however far the nodes moved since. In the pass only ThinTool's own responses
// move nodes (Bullet's collision handlers only append contacts), one pair after another, so one
// running total for the world bounds every node's travel since the refit.

#include <thintool/core/Math.h>

#include <cmath>
#include <limits>

class btCollisionWorld;

namespace thintool::detail {

class CollisionPass {
 public:
  /// Bullet updates the collision objects' boxes after predicting the soft bodies and before it
  /// dispatches the pairs: a swept tool's proxy calls this then.
  void begin() { m_nodeTravel = 0; }
  /// A pair's response moved soft nodes by at most distance (m).
  void recordMoves(Real distance) {
    m_nodeTravel = std::isfinite(distance) && distance >= 0 ? m_nodeTravel + distance
                                                            : std::numeric_limits<Real>::infinity();
  }
  /// A face tree was built during the pass, with leaves that fit their faces exactly.
  void recordUnfittedTree() { m_nodeTravel = std::numeric_limits<Real>::infinity(); }
  /// The farthest any soft node may have moved since its face tree was refitted (m); infinity
  /// when unknown, as before the first pass.
  Real nodeTravel() const { return m_nodeTravel; }

 private:
  Real m_nodeTravel = std::numeric_limits<Real>::infinity();
};

/// Begins a collision pass of world's thintool::CollisionConfiguration as its swept tools' proxies
/// do, for a caller that replays the pass's pairs after restoring the soft nodes (a benchmark).
void beginCollisionPass(btCollisionWorld& world);

}  // namespace thintool::detail
