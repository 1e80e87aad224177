// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The collision algorithm Bullet's dispatcher calls for a soft body and a tool. It owns nothing but
// its links to the tool and the pairs' state, and tells the state when Bullet frees it.

#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>

#include <thintool/core/Math.h>
#include <thintool/response/ResponseTypes.h>

class btCollisionObject;
class btSoftBody;
struct btCollisionObjectWrapper;

namespace thintool {
class Tool;
}

namespace thintool::detail {

class DynamicBody;
struct PairState;

class ToolAlgorithm final : public btCollisionAlgorithm {
 public:
  enum class Mode {
    OnePiece,   ///< discrete detection: the pair of a soft body and one piece of the tool (a compound's child)
    WholeTool,  ///< swept detection: the pair of a soft body and the tool's proxy; every piece
    Idle,       ///< swept detection: the tool body's own pair, which the proxy's pair replaces
  };
  /// state: the piece's pair state (OnePiece); softBody: the soft body (WholeTool).
  ToolAlgorithm(const btCollisionAlgorithmConstructionInfo& info, Tool& tool, Mode mode, PairState* state,
                btSoftBody* softBody, bool swapped);
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
  struct PieceStep;
  // Detection, response and their application for one piece of the tool against a soft body.
  void processPiece(PieceStep& step, const btCollisionObjectWrapper* toolWrap);
  // processPiece's work once the poses are known to be finite: the stages below, in order.
  void processValidPiece(PieceStep& step);
  void beginPieceStep(PieceStep& step);
  void detectForDeformableSolve(PieceStep& step);
  void prepareBuffers(PieceStep& step);
  void gather(PieceStep& step);
  void detect(PieceStep& step);
  void respond(PieceStep& step);
  FrictionSettings pairFrictionSettings(PieceStep& step) const;
  void rememberSweep(PieceStep& step);
  void write(PieceStep& step);
  // The dynamic tool stopped short of the pinned nodes of one pair, or of all its pairs with the soft
  // body that stop it this step (single null).
  void stopAtPinnedNodes(DynamicBody& tool, const btSoftBody& softBody, btScalar timeStep, const PairState* single);
  // The force model on the piece's contacts; reactingBody, when not null, receives the force.
  void computeForces(PieceStep& step, DynamicBody reactingBody);

  Tool& m_tool;
  Mode m_mode;
  PairState* m_state;
  btSoftBody* m_softBody;
  bool m_swapped;
};

}  // namespace thintool::detail
