// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The drop-in: a collision configuration that routes soft-body pairs with registered tools to
/// ThinTool and leaves every other pair to Bullet's stock algorithms.
///
/// Use it where btSoftBodyRigidBodyCollisionConfiguration was used, then register tools:
///
///     thintool::CollisionConfiguration configuration;       // same construction info as stock
///     btCollisionDispatcher dispatcher(&configuration);
///     btSoftRigidDynamicsWorld world(&dispatcher, ...);
///     ...
///     thintool::Tool& spatula = thintool::addTool(world, spatulaBody);
///     world.stepSimulation(dt, 1, dt);
///     const thintool::ToolStepReport& report = spatula.report();
///
/// Threads: like Bullet's stock soft–rigid handler, ThinTool writes into the soft body while the
/// dispatcher runs; use the single-threaded btCollisionDispatcher.

#include <thintool/bullet/Tool.h>
#include <thintool/core/Api.h>

#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>

#include <cstddef>
#include <memory>
#include <vector>

class btCollisionAlgorithm;
class btCollisionObject;
class btCollisionWorld;
class btRigidBody;
struct btCollisionObjectWrapper;
struct btCollisionAlgorithmConstructionInfo;

namespace thintool {

namespace detail {
void beginCollisionPass(btCollisionWorld& world);
}  // namespace detail

class THINTOOL_API CollisionConfiguration : public btSoftBodyRigidBodyCollisionConfiguration {
 public:
  /// Grows info's m_customCollisionAlgorithmMaxElementSize to fit ThinTool's algorithm: Bullet's
  /// pool only asserts the size, so a release build would overrun its slots otherwise.
  explicit CollisionConfiguration(const btDefaultCollisionConstructionInfo& info = btDefaultCollisionConstructionInfo());
  ~CollisionConfiguration() override;

  // See: btSoftBodyRigidBodyCollisionConfiguration::getCollisionAlgorithmCreateFunc
  btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int proxyType0, int proxyType1) override;

  /// The tool registered for object, or nullptr.
  Tool* findTool(const btCollisionObject& object) const;
  /// Bytes ThinTool's collision algorithm takes from the dispatcher's pool.
  static int algorithmSize();
  std::size_t toolCount() const;
  /// The registered tools, in the order they were added.
  const std::vector<Tool*>& tools() const;

 private:
  // Registration goes through thintool::addTool/removeTool, which also re-route the body's
  // existing pairs; the configuration alone cannot reach the broadphase.
  friend Tool& addTool(btCollisionWorld&, btCollisionObject&, const ToolOptions&);
  friend bool removeTool(btCollisionWorld&, const btCollisionObject&);
  friend void detail::beginCollisionPass(btCollisionWorld&);

  struct CreateFunc;
  struct State;
  btCollisionAlgorithm* createAlgorithm(btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                                        const btCollisionObjectWrapper* body1, bool swapped,
                                        btCollisionAlgorithmCreateFunc& stock);
  std::unique_ptr<State> m_state;
};

/// Registers body as a thin tool of world, whose dispatcher must have been built with a
/// thintool::CollisionConfiguration: a btRigidBody (static, kinematic or dynamic), a link of a
/// btMultiBody (btMultiBodyLinkCollider; dynamic where its joints or its free base let it move), or
/// a plain btCollisionObject, which is static or moved by the program like a kinematic body. Builds the
/// tool model from the body's shape: btBoxShape,
/// btConvexHullShape, any other convex shape through the hull of its support points, and each
/// convex child of a btCompoundShape. The body stays awake (DISABLE_DEACTIVATION), since a
/// sleeping tool's pairs are not processed. A kinematic tool is met at the pose of the step's end,
/// as its motion state gave it; a dynamic tool at its pose at the start of the step, as Bullet's
/// stock handler meets it, and it receives the tissue's reaction as impulses (a link through its
/// multibody's joints; ToolStepReport::reaction sums them). Throws
/// thintool::Error naming the tool and the problem.
THINTOOL_API Tool& addTool(btCollisionWorld& world, btCollisionObject& body,
                           const ToolOptions& options = ToolOptions());

/// Unregisters body from world's configuration; returns whether it was a tool. Call it before
/// deleting a tool's body.
THINTOOL_API bool removeTool(btCollisionWorld& world, const btCollisionObject& body);

/// The tool registered for body, or nullptr (also in a world built without ThinTool's
/// configuration).
THINTOOL_API Tool* findTool(btCollisionWorld& world, const btCollisionObject& body);

}  // namespace thintool
