// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The collision algorithm Bullet's dispatcher calls for a (soft body, tool piece) pair. It owns
// nothing but its links to the tool and the pair's state, and tells the state when Bullet frees it.

#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>

namespace thintool {
class Tool;
}

namespace thintool::detail {

struct PairState;

class ToolAlgorithm final : public btCollisionAlgorithm {
 public:
  ToolAlgorithm(const btCollisionAlgorithmConstructionInfo& info, Tool& tool, PairState& state, bool swapped);
  ~ToolAlgorithm() override;

  // See: btCollisionAlgorithm::processCollision
  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;

  // See: btCollisionAlgorithm::calculateTimeOfImpact. Bullet's soft–rigid pairs have no TOI path.
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;
  }

  // Contacts go into the soft body, as with the stock algorithm: there is no manifold.
  void getAllContactManifolds(btManifoldArray&) override {}

 private:
  Tool& m_tool;
  PairState& m_state;
  bool m_swapped;
};

}  // namespace thintool::detail
