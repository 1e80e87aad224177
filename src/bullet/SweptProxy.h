// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The tool's stand-in in Bullet's broadphase for swept detection. Bullet sweeps the box of a
// dynamic body but not of a kinematic one, and never the box of a soft body, so a tool that
// jumps past a thin soft sheet in one step would make no pair with it. The proxy's box is the
// tool's swept box, recomputed when Bullet updates boxes at the start of every step (which is
// also when the tool's motion is tracked); it pairs with soft bodies only, has no contact
// response, and its shape is a point, so that rays and rigid bodies never meet it.

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <unordered_map>

namespace thintool {
class Tool;
}

namespace thintool::detail {

class SweptProxy final : public btCollisionObject {
 public:
  /// registry: the configuration's proxies, which the proxy leaves when it is deleted.
  SweptProxy(Tool& tool, std::unordered_map<const btCollisionObject*, Tool*>& registry);
  /// A program may delete the proxy itself, as Bullet's demos free every object of the world's
  /// array at exit: it leaves the registry and the tool, so that neither points to it after.
  ~SweptProxy() override;
  SweptProxy(const SweptProxy&) = delete;
  SweptProxy& operator=(const SweptProxy&) = delete;
  Tool& tool() const { return m_tool; }

  // See: btCollisionObject::checkCollideWithOverride. Only soft bodies.
  bool checkCollideWithOverride(const btCollisionObject* other) const override;

 private:
  class Shape final : public btSphereShape {
   public:
    explicit Shape(Tool& tool) : btSphereShape(0), m_tool(tool) {}
    // See: btCollisionShape::getAabb. The tool's swept box; the transform is the proxy's own and unused.
    void getAabb(const btTransform& transform, btVector3& outMin, btVector3& outMax) const override;

   private:
    Tool& m_tool;
  };

  Tool& m_tool;
  std::unordered_map<const btCollisionObject*, Tool*>& m_registry;
  Shape m_shape;
};

}  // namespace thintool::detail
