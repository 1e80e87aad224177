// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The gather's walk of Bullet's face tree, shrunk by how far the tree's leaves reach beyond their
// faces (faceLeafSlack), finds the same faces as the walk that trusts the leaves no further; the
// scan of every face finds exactly the faces whose motion meets the box, the walk's and those that
// moved too fast for it.
#include "../../src/bullet/SoftSurface.h"

#include <thintool/bullet/Convert.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace thintool::detail {
namespace {

constexpr btScalar kMargin = 0.05f;
constexpr btScalar kTimeStep = 1.0f / 60;

struct Ball {
  btSoftBodyWorldInfo info;
  std::unique_ptr<btSoftBody> body;
  PairState state;

  Ball() {
    info.m_gravity.setZero();
    body.reset(btSoftBodyHelpers::CreateEllipsoid(info, btVector3(0, 0, 0), btVector3(1, 1, 1), 512));
    body->getCollisionShape()->setMargin(kMargin);
    // Bullet's first prediction sets its margins up (and clears any face tree); the tree ThinTool
    // then builds fits its faces exactly, until the next prediction grows its leaves by the margin.
    body->predictMotion(kTimeStep);
    ensureFaceTree(*body);
    for (int i = 0; i < body->m_nodes.size(); ++i) {
      body->m_nodes[i].m_v = btVector3(0.3f, -0.2f, 0.1f);  // a drift, so that the leaves move
    }
    body->predictMotion(kTimeStep);
    state.lastPositions.resize(body->m_nodes.size());
    state.sweptNodes.reset(static_cast<Index>(body->m_nodes.size()));
  }

  std::vector<Index> gather(const Aabb& box, Real leafSlack) {
    gatherPatch(*body, box, 0, leafSlack, false, state);
    std::vector<Index> faces = state.patch.faceIds;
    releasePatch(state);
    return faces;
  }

  std::vector<Index> scan(const Aabb& box) {
    readFaceCorners(*body, state.faceCorners);
    gatherPatchByScan(*body, box, state);
    std::vector<Index> faces = state.patch.faceIds;
    releasePatch(state);
    return faces;
  }

  // The faces whose corners' box, from where they start the step to where they end it, meets box.
  std::vector<Index> facesMoving(const Aabb& box) const {
    std::vector<Index> faces;
    for (int f = 0; f < body->m_faces.size(); ++f) {
      Aabb motion;
      for (const btSoftBody::Node* node : body->m_faces[f].m_n) {
        motion.include(toVec3(node->m_x));
        motion.include(toVec3(node->m_q));
      }
      if (motion.overlaps(box)) faces.push_back(static_cast<Index>(f));
    }
    return faces;
  }
};

// 200 random boxes around the ball, from seed: visit(box, trial).
template <class Visit>
void forRandomBoxes(unsigned seed, const Visit& visit) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> centre(-1.3, 1.3);
  std::uniform_real_distribution<Real> half(0.001, 0.3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 c{centre(random), centre(random), centre(random)};
    const Vec3 h{half(random), half(random), half(random)};
    visit(Aabb{c - h, c + h}, trial);
  }
}

// The face whose first node is highest.
int topFace(const btSoftBody& body) {
  int top = 0;
  for (int f = 1; f < body.m_faces.size(); ++f) {
    if (body.m_faces[f].m_n[0]->m_x.y() > body.m_faces[top].m_n[0]->m_x.y()) top = f;
  }
  return top;
}

TEST(SoftSurface, TheLeafSlackIsTheMarginLessTheNodesTravel) {
  Ball ball;
  EXPECT_NEAR(faceLeafSlack(*ball.body, 0), kMargin, 1e-7);
  EXPECT_NEAR(faceLeafSlack(*ball.body, 0.02), kMargin - 0.02, 1e-7);
  EXPECT_NEAR(faceLeafSlack(*ball.body, 0.2), kMargin - 0.2, 1e-7);
  EXPECT_EQ(faceLeafSlack(*ball.body, std::numeric_limits<Real>::infinity()), 0);
  ball.body->m_pose.m_bframe = true;  // pose matching moves the nodes after the leaves are fitted
  ball.body->m_cfg.kMT = 0.1f;
  EXPECT_EQ(faceLeafSlack(*ball.body, 0), 0);
  btSoftBodyWorldInfo info;
  std::unique_ptr<btSoftBody> unpredicted(
      btSoftBodyHelpers::CreateEllipsoid(info, btVector3(0, 0, 0), btVector3(1, 1, 1), 64));
  EXPECT_EQ(faceLeafSlack(*unpredicted, 0), 0);
}

TEST(SoftSurface, AWalkShrunkByTheSlackGathersTheSameFaces) {
  Ball ball;
  const Real slack = faceLeafSlack(*ball.body, 0);
  ASSERT_GT(slack, 0);
  std::size_t gathered = 0;
  forRandomBoxes(7, [&](const Aabb& box, int trial) {
    const std::vector<Index> trusting = ball.gather(box, 0);
    EXPECT_EQ(ball.gather(box, slack), trusting) << "trial " << trial;
    gathered += trusting.size();
  });
  EXPECT_GT(gathered, 200u) << "the boxes did meet the ball";
}

TEST(SoftSurface, NodesMovedAfterTheFitAreFoundWhenTheirTravelIsCounted) {
  Ball ball;
  // A face on top, pushed up by four margins after its leaf was fitted (as another tool's
  // response in the same pass would), into a box that its old leaf does not reach.
  btSoftBody& body = *ball.body;
  const int top = topFace(body);
  const Real push = 4 * kMargin;
  Aabb face;
  for (btSoftBody::Node* node : body.m_faces[top].m_n) {
    node->m_x += btVector3(0, btScalar(push), 0);
    face.include(toVec3(node->m_x));
  }
  const Aabb box{{face.center().x - 0.001, face.max.y - 0.001, face.center().z - 0.001},
                 {face.center().x + 0.001, face.max.y + 0.1, face.center().z + 0.001}};
  auto found = [&](Real leafSlack) {
    const std::vector<Index> faces = ball.gather(box, leafSlack);
    return std::find(faces.begin(), faces.end(), static_cast<Index>(top)) != faces.end();
  };
  EXPECT_TRUE(found(faceLeafSlack(body, push)));
  EXPECT_FALSE(found(faceLeafSlack(body, 0))) << "the test's push leaves the face's fitted leaf behind";
}

TEST(SoftSurface, TheScanGathersEveryFaceWhoseMotionMeetsTheBox) {
  Ball ball;
  std::size_t gathered = 0;
  forRandomBoxes(11, [&](const Aabb& box, int trial) {
    const std::vector<Index> scanned = ball.scan(box);
    EXPECT_EQ(scanned, ball.facesMoving(box)) << "trial " << trial;
    const std::vector<Index> walked = ball.gather(box, 0);
    for (const Index f : walked) {
      EXPECT_TRUE(std::binary_search(scanned.begin(), scanned.end(), f)) << "trial " << trial << ", face " << f;
    }
    gathered += scanned.size();
  });
  EXPECT_GT(gathered, 200u) << "the boxes did meet the ball";
}

TEST(SoftSurface, TheScanFindsAFaceThatLeavesTheBoxHoweverFast) {
  Ball ball;
  // A face on top starts the step in a small box and is predicted to end a metre above it, which
  // no bound on the soft nodes' motion near the box foresaw. Its nodes' other faces go with it.
  btSoftBody& body = *ball.body;
  const int top = topFace(body);
  Aabb start;
  for (btSoftBody::Node* node : body.m_faces[top].m_n) {
    start.include(toVec3(node->m_q));
    node->m_x = node->m_q + btVector3(0, 1, 0);
  }
  const auto has = [](const std::vector<Index>& faces, int face) {
    return std::find(faces.begin(), faces.end(), static_cast<Index>(face)) != faces.end();
  };
  EXPECT_TRUE(has(ball.scan(start.expanded(0.001)), top));
  const Vec3 between{start.center().x, start.max.y + 0.5, start.center().z};
  EXPECT_TRUE(has(ball.scan(Aabb{between, between}.expanded(0.001)), top)) << "it passes through there";
  const Vec3 aside = between + Vec3{0.5, 0, 0};
  EXPECT_FALSE(has(ball.scan(Aabb{aside, aside}.expanded(0.001)), top));
}

}  // namespace
}  // namespace thintool::detail
