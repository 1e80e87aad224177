// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "GripperScene.h"

#include "Metrics.h"
#include "SoftBallScene.h"
#include "TetraBlock.h"
#include "WorldKind.h"

#include <thintool/core/Error.h>
#include <thintool/thintool.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftBody.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

namespace thintool::scenes {

namespace {

constexpr double kGravity = 10;                // m/s²
constexpr double kCarriageMass = 2;            // kg
constexpr double kFingerMass = 0.3;            // kg
const btVector3 kFingerHalf(0.01f, 0.08f, 0.1f);  // m: 2 cm thick, 16 cm tall, 20 cm deep
constexpr double kFingerStart = 0.16;          // m, each finger's centre from the gripper's axis
constexpr double kCloseSpeed = 0.1;            // m/s, each finger
constexpr double kCloseGain = 20;              // 1/s: the finger's speed per metre from its closed position
constexpr double kLiftSpeed = 0.2;             // m/s
constexpr double kBaseHeight = 0.5;            // m: the lift's carriage, clear of the body
constexpr double kFingerDrop = 0.4;            // m: the fingers' centres below it, at the body's mid-height

// The soft body's world and, in it, the gripper; Bullet's stock parts or ThinTool's.
struct GripperWorld {
  std::unique_ptr<btCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  std::unique_ptr<btSoftBodySolver> softSolver;
  std::unique_ptr<SoftWorldOfKind> world;

  GripperWorld(WorldKind kind, bool thinTool) {
    if (kind == WorldKind::SoftRigid) throw Error("runGripper: the gripper is a multibody; pick a world that takes one");
    CollisionConfiguration* ours = nullptr;
    if (thinTool) {
      auto configurationOfOurs = std::make_unique<CollisionConfiguration>();
      ours = configurationOfOurs.get();
      configuration = std::move(configurationOfOurs);
    } else {
      configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
    }
    softSolver = softSolverFor(kind, ours);
    dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
    world = std::make_unique<SoftWorldOfKind>(kind, *dispatcher, broadphase, *configuration, *softSolver);
    world->setGravity(btVector3(0, -btScalar(kGravity), 0));
    // The deformable world keeps the finer voxels it sets itself.
    if (kind == WorldKind::SoftMultiBody) world->worldInfo().m_sparsesdf.Initialize();
  }
  ~GripperWorld() { world.reset(); }  // before the parts it was made with
  GripperWorld(const GripperWorld&) = delete;
  GripperWorld& operator=(const GripperWorld&) = delete;
};

// The gripper: a fixed base; link 0, the lift, slides up; links 1 and 2, the fingers, slide
// towards each other across x. Each joint has a velocity motor.
struct Gripper {
  btMultiBody body{3, 0, btVector3(0, 0, 0), true, false};
  btBoxShape fingerShape{kFingerHalf};
  btBoxShape carriageShape{btVector3(0.2f, 0.03f, 0.1f)};
  std::unique_ptr<btMultiBodyLinkCollider> carriage;  // Bullet solves a link's motor in its collider's island
  std::array<std::unique_ptr<btMultiBodyLinkCollider>, 2> fingers;
  std::array<std::unique_ptr<btMultiBodyJointMotor>, 3> motors;
  btMultiBodyDynamicsWorld& world;

  Gripper(btMultiBodyDynamicsWorld& w, double gripForce, double timeStep) : world(w) {
    body.setBasePos(btVector3(0, btScalar(kBaseHeight), 0));
    const btVector3 carriageInertia = btVector3(1, 1, 1) * btScalar(kCarriageMass * 0.01);
    body.setupPrismatic(0, btScalar(kCarriageMass), carriageInertia, -1, btQuaternion::getIdentity(),
                        btVector3(0, 1, 0), btVector3(0, 0, 0), btVector3(0, 0, 0), true);
    btVector3 fingerInertia;
    fingerShape.calculateLocalInertia(btScalar(kFingerMass), fingerInertia);
    for (int f = 0; f < 2; ++f) {
      const btScalar side = f == 0 ? -1 : 1;  // finger 0 on −x, closing along +x
      body.setupPrismatic(f + 1, btScalar(kFingerMass), fingerInertia, 0, btQuaternion::getIdentity(),
                          btVector3(-side, 0, 0), btVector3(side * btScalar(kFingerStart), -btScalar(kFingerDrop), 0),
                          btVector3(0, 0, 0), true);
    }
    body.finalizeMultiDof();
    body.setHasSelfCollision(false);
    world.addMultiBody(&body);
    btAlignedObjectArray<btQuaternion> worldToLocal;
    btAlignedObjectArray<btVector3> localOrigin;
    carriage = std::make_unique<btMultiBodyLinkCollider>(&body, 0);
    carriage->setCollisionShape(&carriageShape);
    body.getLink(0).m_collider = carriage.get();
    for (int f = 0; f < 2; ++f) {
      fingers[f] = std::make_unique<btMultiBodyLinkCollider>(&body, f + 1);
      fingers[f]->setCollisionShape(&fingerShape);
      body.getLink(f + 1).m_collider = fingers[f].get();
    }
    body.updateCollisionObjectWorldTransforms(worldToLocal, localOrigin);
    world.addCollisionObject(carriage.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    for (int f = 0; f < 2; ++f) {
      world.addCollisionObject(fingers[f].get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    }
    const btScalar liftImpulse = btScalar(1000 * timeStep);
    motors[0] = std::make_unique<btMultiBodyJointMotor>(&body, 0, 0, liftImpulse);
    for (int f = 1; f <= 2; ++f) {
      motors[f] = std::make_unique<btMultiBodyJointMotor>(&body, f, 0, btScalar(gripForce * timeStep));
    }
    for (auto& motor : motors) {
      motor->finalizeMultiDof();  // sizes the motor's rows, which getAppliedImpulse reads
      world.addMultiBodyConstraint(motor.get());
    }
  }
  ~Gripper() {
    for (auto& motor : motors) world.removeMultiBodyConstraint(motor.get());
    for (auto& finger : fingers) world.removeCollisionObject(finger.get());
    world.removeCollisionObject(carriage.get());
    world.removeMultiBody(&body);
  }
  Gripper(const Gripper&) = delete;
  Gripper& operator=(const Gripper&) = delete;

  void drive(double liftSpeed, double closeSpeed) {
    motors[0]->setVelocityTarget(btScalar(liftSpeed));
    motors[1]->setVelocityTarget(btScalar(closeSpeed));
    motors[2]->setVelocityTarget(btScalar(closeSpeed));
  }
  // Each finger towards the joint position closed (m), at most at kCloseSpeed: a position
  // controller on the joint's velocity, as a robot's fingers are driven.
  void closeTo(double liftSpeed, double closed) {
    motors[0]->setVelocityTarget(btScalar(liftSpeed));
    for (int f = 1; f <= 2; ++f) {
      const double speed = std::clamp(kCloseGain * (closed - body.getJointPos(f)), -kCloseSpeed, kCloseSpeed);
      motors[f]->setVelocityTarget(btScalar(speed));
    }
  }
  bool finite() const {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(body.getJointPos(i)) || !std::isfinite(body.getJointVel(i))) return false;
    }
    return true;
  }
};

btSoftBody* makeBody(GraspedBody kind, btSoftBodyWorldInfo& info, double mass, double friction) {
  btSoftBody* body = nullptr;
  if (kind == GraspedBody::Cube) {
    body = createTetraBlock(info, Vec3{0, 0.1, 0}, Vec3{0.2, 0.2, 0.2}, {4, 4, 4});
  } else {
    body = createTetraBlock(info, Vec3{0, 0.04, 0}, Vec3{0.08, 0.08, 0.8}, {2, 2, 20});
  }
  body->m_materials[0]->m_kLST = 0.8f;
  body->m_cfg.piterations = 10;
  body->m_cfg.kDF = btScalar(friction);
  body->m_cfg.kDP = 0.01f;
  body->setTotalMass(btScalar(mass));
  body->getCollisionShape()->setMargin(0.01f);
  return body;
}

double verticalMomentum(const btSoftBody& body) {
  double p = 0;
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    if (body.m_nodes[i].m_im > 0) p += body.m_nodes[i].m_v.y() / body.m_nodes[i].m_im;
  }
  return p;
}

bool finiteNodes(const btSoftBody& body) {
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    if (!std::isfinite(body.m_nodes[i].m_x.length2()) || !std::isfinite(body.m_nodes[i].m_v.length2())) return false;
  }
  return true;
}

}  // namespace

const char* graspedBodyName(GraspedBody body) { return body == GraspedBody::Cube ? "cube" : "cable"; }

GripperRun runGripper(const GripperSettings& settings) {
  GripperWorld w(settings.world, settings.thinTool);
  btMultiBodyDynamicsWorld& world = *w.world->multiBody();
  btBoxShape groundShape(btVector3(5, 0.5, 5));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -0.5, 0)));
  world.addRigidBody(&ground);
  btSoftBody* body = makeBody(settings.body, w.world->worldInfo(), settings.bodyMass, settings.bodyFriction);
  const bool deformable = settings.world == WorldKind::Deformable;
  w.world->addSoftBody(body, deformable ? deformableSpringFor(*body, double(body->m_materials[0]->m_kLST),
                                                              settings.timeStep)
                                        : kDeformableSpring);
  if (deformable && !settings.bulletFingerContacts) body->m_cfg.collisions &= ~btSoftBody::fCollision::SDF_MDF;
  Gripper gripper(world, settings.gripForce, settings.timeStep);
  std::array<Tool*, 2> tools{};
  if (settings.thinTool) {
    ToolOptions options;
    options.response.friction.enabled = true;
    options.bullet.deformableNodeContacts = settings.thinToolNodeContacts;
    for (int f = 0; f < 2; ++f) tools[f] = &addTool(world, *gripper.fingers[f], options);
  }

  const double dt = settings.timeStep;
  // The fingers close until each presses settings.squeeze into the body.
  const double halfWidth = settings.body == GraspedBody::Cube ? 0.1 : 0.04;
  const double closed = kFingerStart - double(kFingerHalf.x()) - halfWidth + settings.squeeze;
  const auto stepsOf = [dt](double seconds) { return static_cast<int>(std::lround(seconds / dt)); };
  const int settle = stepsOf(0.5);
  const int close = settle + stepsOf(1.5);
  const int lift = close + stepsOf(settings.liftHeight / kLiftSpeed);
  const int hold = lift + stepsOf(2);
  const int open = hold + stepsOf(1);
  const int loadFrom = hold - stepsOf(1);

  GripperRun run;
  std::vector<Point> nodes = nodePositions(*body);
  const std::vector<std::array<int, 3>> faces = faceIndices(*body);
  std::array<BoxGroundTruth, 2> truths;
  double restHeight = 0;
  std::vector<Point> restNodes;
  std::vector<std::size_t> held;
  double sinkAtLift = 0;
  double lastMomentum = verticalMomentum(*body);
  const double gripperWeight = (kCarriageMass + 2 * kFingerMass) * kGravity;
  int loadSteps = 0;
  int stepsTaken = 0;
  double wallSeconds = 0;
  for (int step = 0; step < open; ++step) {
    if (step < settle) {
      gripper.drive(0, 0);
    } else if (step < close) {
      gripper.closeTo(0, closed);
    } else if (step < lift) {
      gripper.closeTo(kLiftSpeed, closed);
    } else if (step < hold) {
      gripper.closeTo(0, closed);
    } else {
      gripper.drive(0, -kCloseSpeed);
    }
    const auto start = std::chrono::steady_clock::now();
    world.stepSimulation(btScalar(dt), 1, btScalar(dt));
    wallSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    run.finite = run.finite && finiteNodes(*body) && gripper.finite();
    nodes = nodePositions(*body);
    for (int f = 0; f < 2; ++f) {
      const ToolBox box = boxAt(gripper.fingers[f]->getWorldTransform(), toVec3(kFingerHalf));
      if (step == settle - 1) truths[f].start(box, nodes, faces);
      if (step >= settle) truths[f].update(box, nodes, faces);
    }
    const double momentum = verticalMomentum(*body);
    if (step == settle - 1) {
      restHeight = meanHeight(*body);
      restNodes = nodes;
    }
    if (step == close - 1) {
      const double depth = gripper.fingers[0]->getWorldTransform().getOrigin().z();
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (std::abs(nodes[i].z - depth) <= double(kFingerHalf.z())) held.push_back(i);
      }
    }
    const double fingerHeight = gripper.body.getJointPos(0);
    if (step == lift - 1) sinkAtLift = fingerHeight - meanHeight(*body);
    if (step >= loadFrom && step < hold) {
      ++loadSteps;
      run.grip += 0.5 * (std::abs(gripper.motors[1]->getAppliedImpulse(0)) + std::abs(gripper.motors[2]->getAppliedImpulse(0))) / dt;
      run.liftLoad += gripper.motors[0]->getAppliedImpulse(0) / dt - gripperWeight;
      run.bodyLoad += settings.bodyMass * kGravity + (momentum - lastMomentum) / dt;
      for (Tool* tool : tools) {
        if (tool == nullptr) continue;
        const ToolStepReport& report = tool->report();
        run.reportedLoad -= double(deformable ? report.holdWrench.force.y : report.reaction.force.y);
        run.appliedLoad -= double(report.reaction.force.y);
      }
    }
    if (step == hold - 1) {
      run.rise = meanHeight(*body) - restHeight;
      for (const std::size_t i : held) run.heldRise += (nodes[i].y - restNodes[i].y) / double(held.size());
      run.lift = fingerHeight;
      run.slip = (fingerHeight - meanHeight(*body)) - sinkAtLift;
    }
    lastMomentum = momentum;
    ++stepsTaken;
    if (settings.observer && !settings.observer(world, w.world->softBodies(), tools, stepsTaken * dt)) break;
  }
  run.afterRelease = meanHeight(*body) - restHeight;
  const double loadDivisor = std::max(loadSteps, 1);
  run.grip /= loadDivisor;
  run.liftLoad /= loadDivisor;
  run.bodyLoad /= loadDivisor;
  run.reportedLoad /= loadDivisor;
  run.appliedLoad /= loadDivisor;
  for (const BoxGroundTruth& truth : truths) {
    run.crossed += truth.metrics().crossed;
    run.deepest = std::max(run.deepest, truth.metrics().maxPenetration);
    run.piercedSteps += truth.metrics().piercedSteps;
  }
  run.wallMilliseconds = 1000 * wallSeconds / std::max(stepsTaken, 1);

  for (int f = 0; f < 2; ++f) {
    if (tools[f] != nullptr) removeTool(world, *gripper.fingers[f]);
  }
  w.world->removeSoftBody(body);
  delete body;
  world.removeRigidBody(&ground);
  return run;
}

}  // namespace thintool::scenes
