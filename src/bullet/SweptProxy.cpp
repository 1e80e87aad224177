// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SweptProxy.h"

#include "CollisionPass.h"
#include "ToolState.h"

#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletSoftBody/btSoftBody.h>

namespace thintool::detail {

SweptProxy::SweptProxy(Tool& tool, std::unordered_map<const btCollisionObject*, Tool*>& registry)
    : m_tool(tool), m_registry(registry), m_shape(tool) {
  m_registry.emplace(this, &tool);
  setCollisionShape(&m_shape);
  setCollisionFlags(CF_KINEMATIC_OBJECT | CF_NO_CONTACT_RESPONSE);
  setActivationState(DISABLE_DEACTIVATION);
  m_checkCollideWith = 1;
}

SweptProxy::~SweptProxy() {
  m_registry.erase(this);
  if (m_tool.state().proxy == this) m_tool.state().proxy = nullptr;
}

bool SweptProxy::checkCollideWithOverride(const btCollisionObject* other) const {
  return btSoftBody::upcast(other) != nullptr;
}

void SweptProxy::Shape::getAabb(const btTransform& /*transform*/, btVector3& outMin, btVector3& outMax) const {
  // Bullet updates the boxes once a step, after predicting the soft bodies (which refits their
  // face trees) and before dispatching the pairs.
  m_tool.state().trackMotion();
  if (m_tool.state().pass != nullptr) {
    m_tool.state().pass->begin();
  }
  Pose before;
  Pose now;
  m_tool.state().bodyMotion(before, now);
  Aabb box;
  for (Index piece = 0; piece < m_tool.pieceCount(); ++piece) {
    const Aabb& local = m_tool.piece(piece).bounds;
    for (const Pose& body : {before, now}) {
      const Pose pose = body * m_tool.pieceTransform(piece);
      for (int corner = 0; corner < 8; ++corner) {
        box.include(pose.apply({(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                                (corner & 4) ? local.max.z : local.min.z}));
      }
    }
  }
  // The skin, when the tool fixes it; a soft body's own margin is already in its box.
  const Real skin = m_tool.options().skin.value_or(0);
  outMin = toBt(box.min - Vec3{skin, skin, skin});
  outMax = toBt(box.max + Vec3{skin, skin, skin});
}

}  // namespace thintool::detail
