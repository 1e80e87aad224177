// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "CollisionPass.h"
#include "PairState.h"
#include "SweptProxy.h"
#include "ToolAlgorithm.h"
#include "ToolShape.h"
#include "ToolState.h"

#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/core/Error.h>

#include <BulletCollision/BroadphaseCollision/btBroadphaseInterface.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace thintool {

namespace {

btDefaultCollisionConstructionInfo withRoomForToolAlgorithm(btDefaultCollisionConstructionInfo info) {
  info.m_customCollisionAlgorithmMaxElementSize =
      std::max(info.m_customCollisionAlgorithmMaxElementSize, static_cast<int>(sizeof(detail::ToolAlgorithm)));
  return info;
}

// The world's ThinTool configuration, or nullptr in a world built without one.
CollisionConfiguration* findConfiguration(btCollisionWorld& world) {
  auto* dispatcher = dynamic_cast<btCollisionDispatcher*>(world.getDispatcher());
  return dispatcher != nullptr ? dynamic_cast<CollisionConfiguration*>(dispatcher->getCollisionConfiguration())
                               : nullptr;
}

CollisionConfiguration& configurationOf(btCollisionWorld& world) {
  CollisionConfiguration* configuration = findConfiguration(world);
  if (configuration == nullptr) {
    throw Error(
        "the world's btCollisionDispatcher was not built with a thintool::CollisionConfiguration; construct one "
        "where btSoftBodyRigidBodyCollisionConfiguration was constructed");
  }
  return *configuration;
}

// Frees the algorithms of body's existing pairs, so that the next step recreates them through
// the configuration, which then routes them to ThinTool or back to the stock handler.
void reroutePairs(btCollisionWorld& world, const btCollisionObject& body) {
  // The pair cache takes a mutable proxy, though cleaning it changes only the pairs.
  btBroadphaseProxy* proxy = const_cast<btBroadphaseProxy*>(body.getBroadphaseHandle());
  if (proxy != nullptr) {
    world.getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(proxy, world.getDispatcher());
  }
}

}  // namespace

struct CollisionConfiguration::CreateFunc : btCollisionAlgorithmCreateFunc {
  CreateFunc(CollisionConfiguration& configuration, btCollisionAlgorithmCreateFunc* stock, bool swapped)
      : m_configuration(configuration), m_stock(stock) {
    m_swapped = swapped;
  }

  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    return m_configuration.createAlgorithm(info, body0, body1, m_swapped, *m_stock);
  }

  CollisionConfiguration& m_configuration;
  btCollisionAlgorithmCreateFunc* m_stock;
};

struct CollisionConfiguration::State {
  std::unordered_map<const btCollisionObject*, std::unique_ptr<Tool>> tools;
  std::vector<Tool*> toolOrder;  // the same tools in registration order, so that steps are repeatable
  /// Swept tools' broadphase proxies, and their tools.
  std::unordered_map<const btCollisionObject*, Tool*> proxies;
  std::uint64_t toolsCreated = 0;
  std::unique_ptr<CreateFunc> createFunc;
  std::unique_ptr<CreateFunc> swappedCreateFunc;
  /// Shared by the tools: how far their responses moved soft nodes in the current pass.
  detail::CollisionPass pass;

  /// The tool registered for body, or nullptr.
  Tool* find(const btCollisionObject& body) const {
    const auto found = tools.find(&body);
    return found == tools.end() ? nullptr : found->second.get();
  }
  /// The registry's part of thintool::addTool and removeTool.
  Tool& add(btCollisionObject& body, const ToolOptions& options);
  bool remove(const btCollisionObject& body);
};

CollisionConfiguration::CollisionConfiguration(const btDefaultCollisionConstructionInfo& info)
    : btSoftBodyRigidBodyCollisionConfiguration(withRoomForToolAlgorithm(info)), m_state(std::make_unique<State>()) {
  // Every convex type shares the stock soft–convex create functions; box stands for them all.
  m_state->createFunc = std::make_unique<CreateFunc>(
      *this, btSoftBodyRigidBodyCollisionConfiguration::getCollisionAlgorithmCreateFunc(SOFTBODY_SHAPE_PROXYTYPE,
                                                                                          BOX_SHAPE_PROXYTYPE),
      false);
  m_state->swappedCreateFunc = std::make_unique<CreateFunc>(
      *this, btSoftBodyRigidBodyCollisionConfiguration::getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE,
                                                                                          SOFTBODY_SHAPE_PROXYTYPE),
      true);
}

// The tools go first: deleting a swept tool's proxy takes it out of the proxies, which must still
// be there.
CollisionConfiguration::~CollisionConfiguration() {
  m_state->toolOrder.clear();
  m_state->tools.clear();
}

std::size_t CollisionConfiguration::toolCount() const { return m_state->tools.size(); }

const std::vector<Tool*>& CollisionConfiguration::tools() const { return m_state->toolOrder; }

int CollisionConfiguration::algorithmSize() { return static_cast<int>(sizeof(detail::ToolAlgorithm)); }

btCollisionAlgorithm* CollisionConfiguration::createAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                              const btCollisionObjectWrapper* body0,
                                                              const btCollisionObjectWrapper* body1, bool swapped,
                                                              btCollisionAlgorithmCreateFunc& stock) {
  const btCollisionObjectWrapper* softWrap = swapped ? body1 : body0;
  const btCollisionObjectWrapper* toolWrap = swapped ? body0 : body1;
  btSoftBody* softBody = const_cast<btSoftBody*>(btSoftBody::upcast(softWrap->getCollisionObject()));
  using Mode = detail::ToolAlgorithm::Mode;
  auto make = [&](Tool& tool, Mode mode, detail::PairState* state) -> btCollisionAlgorithm* {
    void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(detail::ToolAlgorithm));
    return new (memory) detail::ToolAlgorithm(info, tool, mode, state, softBody, swapped);
  };
  if (softBody != nullptr) {
    const auto proxy = m_state->proxies.find(toolWrap->getCollisionObject());
    if (proxy != m_state->proxies.end()) {
      return make(*proxy->second, Mode::WholeTool, nullptr);
    }
  }
  Tool* tool = findTool(*toolWrap->getCollisionObject());
  if (tool == nullptr || softBody == nullptr) {
    return stock.CreateCollisionAlgorithm(info, body0, body1);
  }
  if (tool->options().swept) {
    return make(*tool, Mode::Idle, nullptr);  // the proxy's pair does the work
  }
  // Children of a compound arrive with their index; a plain convex body is piece 0.
  const Index piece = tool->pieceCount() > 1 || toolWrap->m_index >= 0 ? static_cast<Index>(toolWrap->m_index) : 0;
  if (piece >= tool->pieceCount()) {
    return stock.CreateCollisionAlgorithm(info, body0, body1);
  }
  return make(*tool, Mode::OnePiece, &tool->state().pairState(*softBody, piece));
}

btCollisionAlgorithmCreateFunc* CollisionConfiguration::getCollisionAlgorithmCreateFunc(int proxyType0,
                                                                                       int proxyType1) {
  if (proxyType0 == SOFTBODY_SHAPE_PROXYTYPE && btBroadphaseProxy::isConvex(proxyType1)) {
    return m_state->createFunc.get();
  }
  if (btBroadphaseProxy::isConvex(proxyType0) && proxyType1 == SOFTBODY_SHAPE_PROXYTYPE) {
    return m_state->swappedCreateFunc.get();
  }
  return btSoftBodyRigidBodyCollisionConfiguration::getCollisionAlgorithmCreateFunc(proxyType0, proxyType1);
}

Tool& CollisionConfiguration::State::add(btCollisionObject& body, const ToolOptions& requested) {
  ToolOptions options = requested;
  if (options.name.empty()) {
    options.name = "tool " + std::to_string(toolsCreated + 1);
  }
  auto fail = [&options](const std::string& problem) { throw Error("tool '" + options.name + "': " + problem); };
  if (const Tool* existing = find(body)) {
    fail("this body is already registered, as tool '" + existing->name() + "'");
  }
  if (body.getCollisionShape() == nullptr) {
    fail("the body has no collision shape");
  }
  const std::string optionProblem = validateToolOptions(options);
  if (!optionProblem.empty()) {
    fail(optionProblem);
  }

  std::vector<ToolModel> models;
  std::vector<Pose> transforms;
  try {
    ToolModelSettings settings;
    settings.sampling = options.sampling;
    settings.association = options.association;
    settings.probeDepth = options.probeDepth;
    for (detail::ShapePiece& piece : detail::shapePieces(*body.getCollisionShape())) {
      models.push_back(buildToolModel(piece.mesh, settings));
      transforms.push_back(piece.transform);
    }
  } catch (const Error& error) {
    fail(error.what());
  }

  // The constructor is the configuration's alone: std::make_unique cannot reach it.
  std::unique_ptr<Tool> tool(new Tool(body, options, std::move(models), std::move(transforms)));
  Tool& registered = *tool;
  registered.state().pass = &pass;
  tools.emplace(&body, std::move(tool));
  toolOrder.push_back(&registered);
  ++toolsCreated;
  body.setActivationState(DISABLE_DEACTIVATION);
  return registered;
}

bool CollisionConfiguration::State::remove(const btCollisionObject& body) {
  const auto found = tools.find(&body);
  if (found == tools.end()) {
    return false;
  }
  toolOrder.erase(std::find(toolOrder.begin(), toolOrder.end(), found->second.get()));
  tools.erase(found);
  return true;
}

Tool* CollisionConfiguration::findTool(const btCollisionObject& object) const { return m_state->find(object); }

Tool& addTool(btCollisionWorld& world, btCollisionObject& body, const ToolOptions& options) {
  CollisionConfiguration* configuration = nullptr;
  try {
    configuration = &configurationOf(world);
  } catch (const Error& error) {
    const std::string name = options.name.empty() ? std::string("new tool") : options.name;
    throw Error("tool '" + name + "': " + error.what());
  }
  Tool& tool = configuration->m_state->add(body, options);
  if (tool.options().swept) {
    tool.state().proxy = new detail::SweptProxy(tool, configuration->m_state->proxies);
    world.addCollisionObject(tool.state().proxy, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
  }
  reroutePairs(world, body);
  return tool;
}

bool removeTool(btCollisionWorld& world, const btCollisionObject& body) {
  CollisionConfiguration& configuration = configurationOf(world);
  Tool* tool = configuration.findTool(body);
  if (tool == nullptr) {
    return false;
  }
  // Free the pairs' algorithms before the tool they point to.
  if (tool->state().proxy != nullptr) {
    world.removeCollisionObject(tool->state().proxy);
    delete tool->state().proxy;  // leaves the registry and the tool
  }
  reroutePairs(world, body);
  return configuration.m_state->remove(body);
}

Tool* findTool(btCollisionWorld& world, const btCollisionObject& body) {
  CollisionConfiguration* configuration = findConfiguration(world);
  return configuration != nullptr ? configuration->findTool(body) : nullptr;
}

void detail::beginCollisionPass(btCollisionWorld& world) { configurationOf(world).m_state->pass.begin(); }

}  // namespace thintool
