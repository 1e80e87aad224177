// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ClampScene.h"

#include "Metrics.h"
#include "SoftBallScene.h"
#include "ClampStage.h"
#include "SoftWorld.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace thintool::scenes {

namespace {

// The clamp reaches along +x from a hinge beside the body and closes across z, its jaws standing
// upright: the handle's y axis (the opening direction) is the world's z, its z axis points down.
const btQuaternion kHandleOrientation(btVector3(1, 0, 0), btScalar(kPi / 2));
constexpr double kHingeDistance = 2.3;  // m from the body's centre, along -x

struct Body {
  btVector3 radii;
  int resolution;
};

Body bodyOf(ClampBody kind) {
  return kind == ClampBody::Sphere ? Body{btVector3(1, 1, 1), 63} : Body{btVector3(1.5, 0.35, 0.35), 120};
}

// A jaw as the ground truth's box.
btVector3 momentum(const btSoftBody& body) {
  btVector3 p(0, 0, 0);
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    if (body.m_nodes[i].m_im > 0) p += body.m_nodes[i].m_v / body.m_nodes[i].m_im;
  }
  return p;
}

// The resultant of Bullet's pressure forces on the body for its next step, as btSoftBody's
// applyForces will add them: kPR·area·normal/|volume| at each free node. On a squeezed mesh the
// node areas and normals do not close, so the body's own pressure pushes it as a whole.
btVector3 pressureResultant(btSoftBody& body) {
  btVector3 sum(0, 0, 0);
  if (body.m_cfg.kPR == 0) return sum;
  const btScalar perArea = body.m_cfg.kPR / btFabs(body.getVolume());
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    const btSoftBody::Node& node = body.m_nodes[i];
    if (node.m_im > 0) sum += node.m_n * (node.m_area * perArea);
  }
  return sum;
}

double lowest(const btSoftBody& body) {
  double low = 1e30;
  for (int i = 0; i < body.m_nodes.size(); ++i) low = std::min(low, double(body.m_nodes[i].m_x.y()));
  return low;
}

}  // namespace

ClampStage::ClampStage(ClampBody kind, bool friction, double timeStep, double squeeze) : m_timeStep(timeStep) {
  btSoftRigidDynamicsWorld& world = m_soft.world;
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_sparsesdf.setDefaultVoxelsz(btScalar(0.02));
  info.m_sparsesdf.Reset();
  world.addRigidBody(&m_ground);

  // The baseline's soft material (shared/notes/baseline.md, variant E).
  const Body shape = bodyOf(kind);
  m_body = btSoftBodyHelpers::CreateEllipsoid(info, btVector3(0, shape.radii.y() + 0.3, 0), shape.radii,
                                              shape.resolution);
  m_body->m_materials[0]->m_kLST = 0.5;
  m_body->m_cfg.kDF = 0.5;
  m_body->m_cfg.kPR = 50;
  m_body->m_cfg.kKHR = 1;
  m_body->m_cfg.piterations = 10;
  m_body->m_cfg.kDP = btScalar(1 - std::pow(0.95, 60 * timeStep));
  m_body->setTotalMass(1);
  m_body->getCollisionShape()->setMargin(btScalar(0.05));
  world.addSoftBody(m_body);

  const btScalar dt = btScalar(timeStep);
  for (int i = 0; i < stepsOf(2); ++i) world.stepSimulation(dt, 1, dt);

  m_restCentreHeight = meanHeight(*m_body);
  const double radius = shape.radii.z();  // across the jaws
  m_clampSettings.jawHalfExtents = {1.6, 0.01, 0.3};
  m_clampSettings.jawOptions.response.friction.enabled = friction;
  m_handle = btTransform(kHandleOrientation, btVector3(btScalar(-kHingeDistance), btScalar(m_restCentreHeight), 0));
  m_clamp = std::make_unique<Clamp>(world, m_clampSettings, m_handle, m_clampSettings.maxOpening);
  m_closed = 2 * std::atan((1 - squeeze) * radius / kHingeDistance);

  m_faces = faceIndices(*m_body);
  const auto b = boxes();
  for (int j = 0; j < 2; ++j) m_truths[j].start(b[j], nodePositions(*m_body), m_faces);
  m_lastMomentum = momentum(*m_body);
}

ClampStage::~ClampStage() {
  m_clamp.reset();
  m_soft.world.removeSoftBody(m_body);
  delete m_body;
  m_soft.world.removeRigidBody(&m_ground);
}

int ClampStage::stepsOf(double seconds) const {
  return std::max(1, static_cast<int>(std::lround(seconds / m_timeStep)));
}

double ClampStage::bodyMass() const { return double(m_body->getTotalMass()); }

double ClampStage::centreHeight() const { return meanHeight(*m_body); }

ClampSample ClampStage::step(const btTransform& pose, double opening, const std::string& phase, ClampForces& forces) {
  m_clamp->setPose(pose, opening);
  const btVector3 pressure = pressureResultant(*m_body);
  const btScalar dt = btScalar(m_timeStep);
  const auto start = std::chrono::steady_clock::now();
  m_soft.world.stepSimulation(dt, 1, dt);
  m_wallMicroseconds += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  m_time += m_timeStep;

  forces = m_clamp->forces();
  ClampSample sample;
  sample.time = m_time;
  sample.phase = phase;
  sample.opening = m_clamp->opening();
  sample.grip = forces.grip;
  sample.onUpperJaw = forces.onJaw[0];
  sample.onLowerJaw = forces.onJaw[1];
  sample.onBody = forces.onBody;
  const btVector3 p = momentum(*m_body);
  sample.bodyNetForce = toVec3((p - m_lastMomentum) / dt - m_soft.world.getGravity() * m_body->getTotalMass());
  sample.bodyPressure = toVec3(pressure);
  m_lastMomentum = p;
  sample.bodyLowest = lowest(*m_body);
  sample.bodyCentreHeight = meanHeight(*m_body);
  const auto b = boxes();
  const std::vector<Point> nodes = nodePositions(*m_body);
  for (int j = 0; j < 2; ++j) {
    m_truths[j].update(b[j], nodes, m_faces);
    sample.crossed += m_truths[j].metrics().crossed;
    sample.jawInside = sample.jawInside || m_truths[j].metrics().endsInside;
  }
  return sample;
}

std::array<ToolBox, 2> ClampStage::boxes() {
  return std::array<ToolBox, 2>{
      boxAt(m_clamp->jawBody(0).getWorldTransform(), m_clampSettings.jawHalfExtents),
      boxAt(m_clamp->jawBody(1).getWorldTransform(), m_clampSettings.jawHalfExtents)};
}

const char* clampBodyName(ClampBody body) { return body == ClampBody::Sphere ? "sphere" : "vessel"; }

ClampRun runClamp(const ClampRunSettings& settings) {
  ClampStage stage(settings.body, settings.friction, settings.timeStep, settings.squeeze);
  ClampRun run;
  run.restCentreHeight = stage.restCentreHeight();
  const btTransform handle = stage.handle();
  const double open = stage.open();
  const double closed = stage.closed();

  struct Phase {
    const char* name;
    double seconds;
  };
  const Phase phases[] = {{"close", 1.5}, {"settle", 0.5}, {"lift", 1}, {"hold", settings.holdSeconds},
                          {"release", 0.5}, {"drop", 1.5}};
  int steps = 0;
  double squeezeSum[2] = {0, 0};
  double carrySum[3] = {0, 0, 0};
  int squeezeSamples = 0;
  bool stopped = false;
  for (const Phase& phase : phases) {
    const int count = stage.stepsOf(phase.seconds);
    for (int i = 1; i <= count; ++i) {
      const double s = double(i) / count;
      const std::string name = phase.name;
      double opening = stage.clamp().opening();
      btTransform pose = stage.clamp().handlePose();
      if (name == "close") opening = open + (closed - open) * s;
      if (name == "lift") pose.setOrigin(handle.getOrigin() + btVector3(0, btScalar(settings.liftHeight * s), 0));
      if (name == "release") opening = closed + (open - closed) * s;
      ClampForces forces;
      const ClampSample sample = stage.step(pose, opening, name, forces);
      ++steps;
      run.crossed = sample.crossed;
      run.jawEverInside = run.jawEverInside || sample.jawInside;
      if (name == "hold" && sample.time > 0) {
        // The hold's last second: the squeeze each jaw feels along the closing axis (world z).
        const int last = stage.stepsOf(1);
        if (i > count - last) {
          squeezeSum[0] += forces.onJaw[0].z;
          squeezeSum[1] += forces.onJaw[1].z;
          carrySum[0] += sample.onBody.y;
          carrySum[1] += sample.bodyPressure.y;
          carrySum[2] += sample.bodyNetForce.y;
          ++squeezeSamples;
        }
        if (i == count) run.liftedCentreHeight = sample.bodyCentreHeight;
      }
      run.samples.push_back(sample);
      if (settings.observer && !settings.observer(stage.world(), stage.clamp(), sample)) {
        stopped = true;
        break;
      }
    }
    if (stopped) break;
  }
  run.droppedCentreHeight = stage.centreHeight();
  run.upperSqueeze = squeezeSamples > 0 ? squeezeSum[0] / squeezeSamples : 0;
  run.lowerSqueeze = squeezeSamples > 0 ? squeezeSum[1] / squeezeSamples : 0;
  if (squeezeSamples > 0) {
    run.jawsCarry = carrySum[0] / squeezeSamples;
    run.pressureCarries = carrySum[1] / squeezeSamples;
    run.momentumBalance = carrySum[2] / squeezeSamples;
  }
  run.microsecondsPerStep = stage.wallMicroseconds() / steps;
  return run;
}

}  // namespace thintool::scenes
