// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/thintool.h>
#include <thintool/bullet/DeformableBodySolver.h>

#include "WorldKind.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <LinearMath/btPoolAllocator.h>
#include <btBulletDynamicsCommon.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include <memory>
#include <string>

namespace thintool {
namespace {

// A world built on a given collision configuration, and one kinematic body to register.
struct World {
  explicit World(std::unique_ptr<btCollisionConfiguration> config)
      : configuration(std::move(config)),
        dispatcher(configuration.get()),
        world(&dispatcher, &broadphase, &solver, configuration.get(), &softSolver),
        motion(btTransform::getIdentity()),
        body(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &box)) {
    world.addRigidBody(&body);
  }
  ~World() { world.removeRigidBody(&body); }

  std::unique_ptr<btCollisionConfiguration> configuration;
  btCollisionDispatcher dispatcher;
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDefaultSoftBodySolver softSolver;
  btSoftRigidDynamicsWorld world;
  btBoxShape box{btVector3(0.4, 0.01, 0.4)};
  btDefaultMotionState motion;
  btRigidBody body;
};

std::string errorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(Configuration, PoolSlotsFitThinToolsAlgorithm) {
  btDefaultCollisionConstructionInfo info;
  info.m_customCollisionAlgorithmMaxElementSize = 0;
  CollisionConfiguration configuration(info);
  EXPECT_GE(configuration.getCollisionAlgorithmPool()->getElementSize(), CollisionConfiguration::algorithmSize());
}

TEST(Configuration, AWorldWithoutThinToolsConfigurationIsAClearError) {
  World stock(std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>());
  ToolOptions options;
  options.name = "spatula";
  const std::string message = errorOf([&] { addTool(stock.world, stock.body, options); });
  EXPECT_NE(message.find("spatula"), std::string::npos) << message;
  EXPECT_NE(message.find("thintool::CollisionConfiguration"), std::string::npos) << message;
}

TEST(Configuration, RegistersOnceAndUnregisters) {
  World w(std::make_unique<CollisionConfiguration>());
  Tool& tool = addTool(w.world, w.body);
  EXPECT_EQ(tool.name(), "tool 1");
  EXPECT_EQ(findTool(w.world, w.body), &tool);
  EXPECT_EQ(w.body.getActivationState(), DISABLE_DEACTIVATION);
  EXPECT_NE(errorOf([&] { addTool(w.world, w.body); }).find("already registered"), std::string::npos);
  EXPECT_TRUE(removeTool(w.world, w.body));
  EXPECT_EQ(findTool(w.world, w.body), nullptr);
  EXPECT_FALSE(removeTool(w.world, w.body));
}

TEST(Configuration, FindToolInAStockWorldIsNull) {
  World stock(std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>());
  EXPECT_EQ(findTool(stock.world, stock.body), nullptr);
}

TEST(Configuration, RegisteringABodyTwiceNamesTheToolItIs) {
  World w(std::make_unique<CollisionConfiguration>());
  ToolOptions first;
  first.name = "spatula";
  addTool(w.world, w.body, first);
  ToolOptions second;
  second.name = "scalpel";
  const std::string message = errorOf([&] { addTool(w.world, w.body, second); });
  EXPECT_NE(message.find("already registered, as tool 'spatula'"), std::string::npos) << message;
}

// Bullet's demos free every object of the world's array at exit, then the world, then the
// configuration: the swept tool's proxy is among the objects, and must be freed once.
TEST(Configuration, AProgramMayFreeEveryObjectOfTheWorldItself) {
  auto* configuration = new CollisionConfiguration();
  auto* dispatcher = new btCollisionDispatcher(configuration);
  auto* broadphase = new btDbvtBroadphase();
  auto* solver = new btSequentialImpulseConstraintSolver();
  auto* softSolver = new SoftBodySolver(*configuration);
  auto* world = new btSoftRigidDynamicsWorld(dispatcher, broadphase, solver, configuration, softSolver);
  auto* shape = new btBoxShape(btVector3(0.4, 0.01, 0.4));
  auto* body = new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(0, new btDefaultMotionState(), shape));
  world->addRigidBody(body);
  ASSERT_TRUE(addTool(*world, *body).options().swept);
  EXPECT_EQ(world->getNumCollisionObjects(), 2);  // the body and its swept proxy
  world->stepSimulation(1.0 / 60, 1, 1.0 / 60);
  // As Bullet's demos exit: every object of the array, then the world and what it was built on.
  for (int i = world->getNumCollisionObjects() - 1; i >= 0; --i) {
    btCollisionObject* object = world->getCollisionObjectArray()[i];
    if (btRigidBody* rigid = btRigidBody::upcast(object)) delete rigid->getMotionState();
    world->removeCollisionObject(object);
    delete object;
  }
  EXPECT_EQ(world->getNumCollisionObjects(), 0);
  delete world;
  delete softSolver;
  delete solver;
  delete broadphase;
  delete dispatcher;
  delete configuration;  // the tool is still registered; its proxy is gone, and it knows
  delete shape;
}

TEST(Configuration, InvalidOptionsNameTheToolAndTheField) {
  World w(std::make_unique<CollisionConfiguration>());
  ToolOptions options;
  options.name = "clamp jaw";
  options.response.stiffness = -5;
  std::string message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("clamp jaw"), std::string::npos) << message;
  EXPECT_NE(message.find("response.stiffness"), std::string::npos) << message;

  options = ToolOptions{};
  options.association.enabled = false;  // check 1 still on
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("filters.check1"), std::string::npos) << message;

  for (const Real speed : {Real(0), Real(-1), Real(std::nan(""))}) {
    options = ToolOptions{};
    options.skinGrowthSpeed = speed;
    message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("skinGrowthSpeed"), std::string::npos) << message;
  }

  // Lengths left empty are the library's to pick; given, they must be lengths.
  for (const Real skin : {Real(-0.01), Real(std::nan("")), Real(INFINITY)}) {
    options = ToolOptions{};
    options.skin = skin;
    message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("skin"), std::string::npos) << message;
  }
  options = ToolOptions{};
  options.probeDepth = 0;
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("probeDepth"), std::string::npos) << message;
  options = ToolOptions{};
  options.filters.reverseRayLength = 0;
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("filters.reverseRayLength"), std::string::npos) << message;
  options = ToolOptions{};
  options.skin = 0;  // no skin at all is a choice
  options.probeDepth = 0.01;
  options.filters.reverseRayLength = 2;
  EXPECT_NO_THROW(addTool(w.world, w.body, options));
  EXPECT_TRUE(removeTool(w.world, w.body));

  for (const Real reach : {Real(-1), Real(std::nan("")), Real(INFINITY)}) {
    options = ToolOptions{};
    options.bullet.holdPlaneReach = reach;
    message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("bullet.holdPlaneReach"), std::string::npos) << message;
  }
  for (const Real factor : {Real(0.5), Real(std::nan("")), Real(INFINITY)}) {
    options = ToolOptions{};
    options.energyGuard.speedFactor = factor;
    message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("energyGuard.speedFactor"), std::string::npos) << message;
  }
  options = ToolOptions{};
  options.energyGuard.energySlack = -0.1;
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("energyGuard.energySlack"), std::string::npos) << message;
  options = ToolOptions{};
  options.energyGuard.restingSpeed = -1;
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("energyGuard.restingSpeed"), std::string::npos) << message;
  options.energyGuard.enabled = false;  // a guard that is off is not checked
  EXPECT_NO_THROW(addTool(w.world, w.body, options));
  EXPECT_TRUE(removeTool(w.world, w.body));

  options = ToolOptions{};
  options.sampling.spacing = std::nan("");
  message = errorOf([&] { addTool(w.world, w.body, options); });
  EXPECT_NE(message.find("sampling.spacing"), std::string::npos) << message;
  EXPECT_EQ(findTool(w.world, w.body), nullptr) << "a failed registration leaves nothing behind";
  EXPECT_NO_THROW(addTool(w.world, w.body, ToolOptions::rayOnly()));
}

TEST(Configuration, InvalidForceOptionsNameTheField) {
  World w(std::make_unique<CollisionConfiguration>());
  const std::pair<std::function<void(ForceSettings&)>, const char*> cases[] = {
      {[](ForceSettings& f) { f.huntCrossley.stiffness = -1; }, "force.huntCrossley.stiffness"},
      {[](ForceSettings& f) { f.huntCrossley.exponent = 0; }, "force.huntCrossley.exponent"},
      {[](ForceSettings& f) { f.huntCrossley.exponent = -1.5; }, "force.huntCrossley.exponent"},
      {[](ForceSettings& f) { f.huntCrossley.damping = std::nan(""); }, "force.huntCrossley.damping"},
      {[](ForceSettings& f) { f.rateCutoff = -30; }, "force.rateCutoff"},
      {[](ForceSettings& f) { f.touchTolerance = INFINITY; }, "force.touchTolerance"},
      {[](ForceSettings& f) { f.torquePoint = {0, std::nan(""), 0}; }, "force.torquePoint"},
  };
  for (const auto& [spoil, field] : cases) {
    ToolOptions options;
    options.name = "spatula";
    options.force.enabled = true;
    spoil(options.force);
    const std::string message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("spatula"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
    EXPECT_EQ(findTool(w.world, w.body), nullptr);
  }
  ToolOptions off;
  off.force.huntCrossley.exponent = -1;  // not checked while the force model is off
  EXPECT_NO_THROW(addTool(w.world, w.body, off));
}

TEST(Configuration, InvalidFrictionNamesTheField) {
  World w(std::make_unique<CollisionConfiguration>());
  const std::pair<std::function<void(FrictionSettings&)>, const char*> cases[] = {
      {[](FrictionSettings& f) { f.staticCoefficient = -0.1; }, "response.friction.staticCoefficient"},
      {[](FrictionSettings& f) { f.kineticCoefficient = std::nan(""); }, "response.friction.kineticCoefficient"},
      {[](FrictionSettings& f) { f.kineticCoefficient = f.staticCoefficient + 0.1; },
       "response.friction.kineticCoefficient"},
  };
  for (const auto& [spoil, field] : cases) {
    ToolOptions options;
    options.name = "jaw";
    options.response.friction.enabled = true;
    spoil(options.response.friction);
    const std::string message = errorOf([&] { addTool(w.world, w.body, options); });
    EXPECT_NE(message.find("jaw"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
  }
}

TEST(Configuration, NonConvexShapesAreRejected) {
  World w(std::make_unique<CollisionConfiguration>());
  btTriangleMesh mesh;
  mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1));
  btBvhTriangleMeshShape concave(&mesh, true);
  w.body.setCollisionShape(&concave);
  const std::string message = errorOf([&] { addTool(w.world, w.body); });
  EXPECT_NE(message.find("not convex"), std::string::npos) << message;
  w.body.setCollisionShape(&w.box);
}

// Bullet's deformable world collides the pair itself, with swept and discrete tools alike, where
// the tool keeps Bullet's own node contacts (BulletSettings::deformableNodeContacts off; a discrete
// tool always does).
TEST(Configuration, DeformableWorldPairsGoToBulletAndAreCounted) {
  for (const bool swept : {true, false}) {
    CollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btDeformableBodySolver deformableSolver;
    btDeformableMultiBodyConstraintSolver solver;
    solver.setDeformableSolver(&deformableSolver);
    btDeformableMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration, &deformableSolver);
    btSoftBody* ball = btSoftBodyHelpers::CreateEllipsoid(world.getWorldInfo(), btVector3(0, 0, 0),
                                                          btVector3(1, 1, 1), 63);
    ball->m_cfg.collisions = btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDN;
    ball->setTotalMass(1);
    world.addSoftBody(ball);
    btBoxShape plateShape(btVector3(0.4, 0.01, 0.4));
    btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.0, 0)));
    btRigidBody plate(btRigidBody::btRigidBodyConstructionInfo(0, &motion, &plateShape));
    plate.setCollisionFlags(plate.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    world.addRigidBody(&plate);
    ToolOptions options;
    options.swept = swept;
    options.bullet.deformableNodeContacts = false;
    Tool& tool = addTool(world, plate, options);
    for (int i = 0; i < 3; ++i) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
    const ToolStepReport& report = tool.report();
    EXPECT_GT(report.diagnostics.stockPairs.deformableWorld, 0u) << swept;
    EXPECT_EQ(report.diagnostics.stockPairs.total(), report.diagnostics.stockPairs.deformableWorld) << swept;
    EXPECT_TRUE(report.contacts.empty()) << swept;
    EXPECT_GT(ball->m_nodeRigidContacts.size() + ball->m_faceRigidContacts.size(), 0) << swept;
    removeTool(world, plate);
    world.removeRigidBody(&plate);
    world.removeSoftBody(ball);
    delete ball;
  }
}

// A unit ball of 128 faces dropped on a ground box in Bullet's deformable world, the box a tool of
// the configuration when asked.
struct DeformableBallOnGround {
  btCollisionDispatcher dispatcher;
  btDbvtBroadphase broadphase;
  scenes::SoftWorldOfKind world;
  btBoxShape groundShape{btVector3(2, 0.1, 2)};
  btDefaultMotionState motion{btTransform(btQuaternion::getIdentity(), btVector3(0, -0.1, 0))};
  btRigidBody ground{btRigidBody::btRigidBodyConstructionInfo(0, &motion, &groundShape)};
  btSoftBody* ball = nullptr;
  Tool* tool = nullptr;

  DeformableBallOnGround(btCollisionConfiguration& configuration, btSoftBodySolver& softSolver, bool groundIsTool)
      : dispatcher(&configuration),
        world(scenes::WorldKind::Deformable, dispatcher, broadphase, configuration, softSolver) {
    world.world().setGravity(btVector3(0, -10, 0));
    ball = btSoftBodyHelpers::CreateEllipsoid(world.worldInfo(), btVector3(0, 1.2, 0), btVector3(1, 1, 1), 63);
    ball->setTotalMass(1);
    world.addSoftBody(ball);
    world.world().addRigidBody(&ground);
    if (groundIsTool) tool = &addTool(world.world(), ground);
  }
  ~DeformableBallOnGround() {
    if (tool != nullptr) removeTool(world.world(), ground);
    world.world().removeRigidBody(&ground);
    world.removeSoftBody(ball);
    delete ball;
  }
  DeformableBallOnGround(const DeformableBallOnGround&) = delete;
  DeformableBallOnGround& operator=(const DeformableBallOnGround&) = delete;

  void step(int steps) {
    for (int i = 0; i < steps; ++i) world.world().stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
  }
};

// ThinTool's deformable solver changes nothing without a tool: a ball dropped on a box in the
// deformable world steps bit for bit as with Bullet's own solver and configuration. With the box
// registered as a tool, its node contacts in Bullet's solve are ThinTool's, and its last word runs
// after the solve.
TEST(Configuration, TheDeformableSolverWithoutToolsStepsAsBulletsAndSpeaksLastWithOne) {
  const auto drop = [](bool thinTool, bool registerTool) {
    std::unique_ptr<btCollisionConfiguration> configuration;
    std::unique_ptr<btSoftBodySolver> softSolver;
    if (thinTool) {
      auto ours = std::make_unique<CollisionConfiguration>();
      softSolver = scenes::softSolverFor(scenes::WorldKind::Deformable, ours.get());
      configuration = std::move(ours);
    } else {
      configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
      softSolver = scenes::softSolverFor(scenes::WorldKind::Deformable, nullptr);
    }
    DeformableBallOnGround scene(*configuration, *softSolver, registerTool);
    scene.step(90);
    std::vector<btVector3> nodes;
    for (int i = 0; i < scene.ball->m_nodes.size(); ++i) nodes.push_back(scene.ball->m_nodes[i].m_x);
    if (scene.tool != nullptr) {
      const ToolStepReport& report = scene.tool->report();
      EXPECT_TRUE(report.diagnostics.lastWord.ran);
      EXPECT_EQ(report.diagnostics.stockPairs.deformableWorld, 0u);
      EXPECT_GT(report.diagnostics.deformableNodeContacts, 0u);
      EXPECT_EQ(report.diagnostics.lastWord.violations(), 0u);
    }
    return nodes;
  };
  const std::vector<btVector3> stock = drop(false, false);
  const std::vector<btVector3> ours = drop(true, false);
  ASSERT_EQ(stock.size(), ours.size());
  for (std::size_t i = 0; i < stock.size(); ++i) {
    EXPECT_EQ(stock[i].x(), ours[i].x());
    EXPECT_EQ(stock[i].y(), ours[i].y());
    EXPECT_EQ(stock[i].z(), ours[i].z());
  }
  EXPECT_LT(stock[0].y(), 1.0) << "the ball fell";
  const std::vector<btVector3> held = drop(true, true);
  for (const btVector3& node : held) EXPECT_GT(node.y(), -0.01) << "no node ends inside the ground";
}

// Bullet's face contact on a sliver face can come back with NaN weights in the float build; with a
// tool registered the deformable solver drops such a contact before Bullet's solve reads it.
TEST(Configuration, TheDeformableSolverDropsContactsThatAreNotFinite) {
  CollisionConfiguration configuration;
  DeformableBodySolver solver(configuration);
  DeformableBallOnGround scene(configuration, solver, true);
  scene.step(60);
  EXPECT_EQ(solver.droppedContacts(), 0);
  // The ball rests on the ground: its last step's contacts are still there, and one of them, made
  // not finite, joins them.
  btSoftBody& ball = *scene.ball;
  ASSERT_GT(ball.m_faceRigidContacts.size(), 0);
  const int finite = ball.m_faceRigidContacts.size();
  btSoftBody::DeformableFaceRigidContact broken = ball.m_faceRigidContacts[0];
  broken.m_bary.setX(std::numeric_limits<btScalar>::quiet_NaN());
  broken.m_weights = broken.m_bary;
  ball.m_faceRigidContacts.push_back(broken);
  solver.setConstraints(scene.world.world().getSolverInfo());
  EXPECT_EQ(solver.droppedContacts(), 1);
  EXPECT_EQ(ball.m_faceRigidContacts.size(), finite);
  scene.step(30);
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    EXPECT_TRUE(std::isfinite(ball.m_nodes[i].m_x.length2())) << "node " << i;
  }
}

// In the deformable world a tool carries what Bullet's contacts apply to it: a ball resting on a
// ground box registered as a tool loads it with its weight, as the ball's momentum balance says
// (m g + dp/dt, which alternates step by step with the ball's contacts), within 5 % over a second.
TEST(Configuration, TheDeformableWorldsContactsLoadTheToolWithWhatTheyCarry) {
  CollisionConfiguration configuration;
  DeformableBodySolver solver(configuration);
  DeformableBallOnGround scene(configuration, solver, true);
  scene.ball->setActivationState(DISABLE_DEACTIVATION);  // a sleeping body has no contacts to read
  const btSoftBody& ball = *scene.ball;
  const auto momentum = [&] {
    double p = 0;
    for (int i = 0; i < ball.m_nodes.size(); ++i) p += double(ball.m_nodes[i].m_v.y()) / double(ball.m_nodes[i].m_im);
    return p;
  };
  scene.step(420);
  constexpr int kSteps = 60;
  const double weight = 10 * 1.0;  // g·m: the scene's 10 m/s² and 1 kg
  double carried = 0;
  double balance = 0;
  double before = momentum();
  for (int i = 0; i < kSteps; ++i) {
    scene.step(1);
    const ToolStepReport& report = scene.tool->report();
    carried += -report.holdWrench.force.y / kSteps;
    const double now = momentum();
    balance += (weight + (now - before) * 60) / kSteps;
    before = now;
    EXPECT_EQ(report.diagnostics.lastWord.violations(), 0u);
  }
  EXPECT_NEAR(balance, weight, 0.05 * weight) << "the ball rests";
  EXPECT_NEAR(carried, balance, 0.05 * balance);
}

}  // namespace
}  // namespace thintool

