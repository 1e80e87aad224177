// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SoftBallScene.h"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <LinearMath/btConvexHullComputer.h>

#include "geometry/RayTriangle.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace thintool::scenes {

namespace {

constexpr double kParkedHeight = 50;  // m: where the tool waits while the ball settles

}  // namespace

SoftVariant softVariantOf(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::StockA:
      return {0.25, 0.1, 1, 0.25};
    case Algorithm::StockB:
      return {0.25, 1, 10, 0.25};
    case Algorithm::StockE:
    case Algorithm::ThinToolPaper:
    case Algorithm::ThinTool:
      break;
  }
  return {0.05, 1, 10, 0.02};
}

// CreateEllipsoid's ball with every one of its points kept (SceneSettings::exactBallHull). The
// points are the same Hammersley set on the sphere: heights from the base-2 radical inverse of the
// point's index, angles evenly spread. btConvexHullComputer joins them, but it rounds its input to
// 1/10,216 of the box's extent, and past some 8,000 points on a unit ball that drops points the
// sphere's curvature no longer lifts above their neighbours' plane (657 of 32,770 for res 32,767);
// each is put back into the face it lies over, split in three. Every point is then a node, and a
// closed surface of V nodes has 2·V - 4 faces.
btSoftBody* createExactHullEllipsoid(btSoftBodyWorldInfo& info, const btVector3& centre, const btVector3& radii,
                                     int res) {
  const int count = res + 3;
  std::vector<Vec3> points(static_cast<std::size_t>(count));
  const Vec3 middle{centre.x(), centre.y(), centre.z()};
  for (int i = 0; i < count; ++i) {
    double inverse = 0;
    double weight = 0.5;
    for (unsigned bits = static_cast<unsigned>(i); bits != 0; bits >>= 1, weight *= 0.5) {
      inverse += (bits & 1U) != 0 ? weight : 0;
    }
    const double z = 2 * inverse - 1;
    const double angle = kPi * (1 + 2.0 * i) / count;
    const double ring = std::sqrt(1 - z * z);
    points[static_cast<std::size_t>(i)] =
        middle + Vec3{ring * std::cos(angle) * radii.x(), ring * std::sin(angle) * radii.y(), z * radii.z()};
  }
  btConvexHullComputer hull;
  hull.compute(&points[0].x, static_cast<int>(sizeof(Vec3)), count, 0, 0);

  // The hull's faces, on the input's indices (its own vertices are the rounded points), as fans.
  std::vector<std::array<int, 3>> faces;
  std::vector<char> kept(points.size(), 0);
  std::vector<int> polygon;
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    polygon.clear();
    const btConvexHullComputer::Edge* edge = first;
    do {
      polygon.push_back(hull.original_vertex_index[edge->getSourceVertex()]);
      edge = edge->getNextEdgeOfFace();
    } while (edge != first);
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
    for (int corner : polygon) {
      kept[static_cast<std::size_t>(corner)] = 1;
    }
  }
  Real longestEdge = 0;
  for (const auto& face : faces) {
    for (int k = 0; k < 3; ++k) {
      longestEdge = std::max(longestEdge, length(points[face[k]] - points[face[(k + 1) % 3]]));
    }
  }
  for (int i = 0; i < count; ++i) {
    if (kept[static_cast<std::size_t>(i)] != 0) {
      continue;
    }
    const Vec3& p = points[static_cast<std::size_t>(i)];
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const std::array<int, 3> face = faces[f];
      // A point inside a triangle is no farther than its longest edge from a corner.
      if (length(p - points[face[0]]) > longestEdge) {
        continue;
      }
      if (intersectSegmentTriangle(middle, (p - middle) * 2, points[face[0]], points[face[1]], points[face[2]]).hit) {
        faces[f] = {face[0], face[1], i};
        faces.push_back({face[1], face[2], i});
        faces.push_back({face[2], face[0], i});
        break;
      }
    }
  }

  std::vector<btVector3> nodes;
  nodes.reserve(points.size());
  for (const Vec3& p : points) {
    nodes.emplace_back(btScalar(p.x), btScalar(p.y), btScalar(p.z));
  }
  auto* body = new btSoftBody(&info, count, nodes.data(), nullptr);
  for (const auto& face : faces) {
    // Each edge of a closed, consistently wound surface is run once each way: link it once.
    for (int k = 0; k < 3; ++k) {
      if (face[k] < face[(k + 1) % 3]) {
        body->appendLink(face[k], face[(k + 1) % 3]);
      }
    }
    body->appendFace(face[0], face[1], face[2]);
  }
  body->randomizeConstraints();  // as CreateEllipsoid
  return body;
}

const char* algorithmName(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::StockA:
      return "stock A (defaults)";
    case Algorithm::StockB:
      return "stock B (kKHR 1, 10 it.)";
    case Algorithm::StockE:
      return "stock E (B, skin 0.05)";
    case Algorithm::ThinToolPaper:
      return "ThinTool, paper (discrete)";
    case Algorithm::ThinTool:
      break;
  }
  return "ThinTool, swept (default)";
}

const char* toolShapeName(ToolShape shape) {
  switch (shape) {
    case ToolShape::Plate:
      return "plate";
    case ToolShape::Needle:
      return "needle";
    case ToolShape::SplitPlate:
      break;
  }
  return "split plate";
}

struct SoftBallScene::Bullet {
  std::unique_ptr<btCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  std::unique_ptr<btSoftBodySolver> softSolver;
  btBoxShape groundShape{btVector3(20, 1, 20)};
  btDefaultMotionState groundMotion;
  std::unique_ptr<btRigidBody> ground;
  std::unique_ptr<btBoxShape> toolShape;
  std::unique_ptr<btBoxShape> halfShape;
  std::unique_ptr<btCompoundShape> compound;
  btDefaultMotionState toolMotion;
  std::unique_ptr<btRigidBody> tool;
};

SoftBallScene::SoftBallScene(const SceneSettings& settings)
    : m_settings(settings), m_centreX(settings.origin[0]), m_centreZ(settings.origin[2]), m_bullet(new Bullet) {
  Bullet& b = *m_bullet;
  const SoftVariant variant = softVariantOf(settings.algorithm);
  const bool thinTool = settings.algorithm == Algorithm::ThinTool || settings.algorithm == Algorithm::ThinToolPaper;
  if (thinTool) {
    auto configuration = std::make_unique<thintool::CollisionConfiguration>();
    b.softSolver = softSolverFor(settings.world, configuration.get());
    b.configuration = std::move(configuration);
  } else {
    b.configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
    b.softSolver = softSolverFor(settings.world, nullptr);
  }
  b.dispatcher = std::make_unique<btCollisionDispatcher>(b.configuration.get());
  m_world = std::make_unique<SoftWorldOfKind>(settings.world, *b.dispatcher, b.broadphase, *b.configuration,
                                              *b.softSolver);
  m_world->world().setGravity(btVector3(0, -10, 0));
  btSoftBodyWorldInfo& info = worldInfo();
  info.m_gravity = m_world->world().getGravity();
  info.m_sparsesdf.setDefaultVoxelsz(btScalar(variant.voxel));
  info.m_sparsesdf.Reset();

  b.groundMotion.setWorldTransform(btTransform(btQuaternion::getIdentity(), atOrigin(0, -1, 0)));
  b.toolMotion.setWorldTransform(btTransform(btQuaternion::getIdentity(), atOrigin(0, kParkedHeight, 0)));
  b.ground = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, &b.groundMotion, &b.groundShape));
  m_world->world().addRigidBody(b.ground.get());

  m_ball = settings.exactBallHull
               ? createExactHullEllipsoid(info, atOrigin(0, 1.3, 0), btVector3(1, 1, 1), settings.ballResolution)
               : btSoftBodyHelpers::CreateEllipsoid(info, atOrigin(0, 1.3, 0), btVector3(1, 1, 1),
                                                    settings.ballResolution);
  m_ball->m_materials[0]->m_kLST = 0.5;
  m_ball->m_cfg.kDF = 0.5;
  m_ball->m_cfg.kPR = 50;
  m_ball->m_cfg.kKHR = btScalar(variant.kKHR);
  m_ball->m_cfg.piterations = variant.positionIterations;
  // The same damping per second at every time step.
  m_ball->m_cfg.kDP = btScalar(1 - std::pow(0.95, 60 * settings.timeStep / settings.substeps));
  m_ball->setTotalMass(1);
  m_ball->getCollisionShape()->setMargin(btScalar(variant.margin));
  // In the deformable world the finer balls' lighter nodes get springs of the same frequency:
  // kDeformableSpring on the 4,096-face ball's nodes, a 31st of the 128-face ball's, flung them
  // within a few steps of the plate's touch.
  m_world->addSoftBody(m_ball, ballSpringFor(*m_ball));

  const btScalar halfThickness = btScalar(settings.toolThickness / 2);
  const btVector3 half = settings.tool == ToolShape::Needle ? btVector3(0.5, halfThickness, halfThickness)
                                                            : btVector3(0.4, halfThickness, 0.4);
  b.toolShape = std::make_unique<btBoxShape>(half);
  b.toolShape->setMargin(btScalar(0.001));
  btCollisionShape* toolShape = b.toolShape.get();
  if (settings.tool == ToolShape::SplitPlate) {
    b.halfShape = std::make_unique<btBoxShape>(btVector3(0.2, halfThickness, 0.4));
    b.halfShape->setMargin(btScalar(0.001));
    b.compound = std::make_unique<btCompoundShape>();
    b.compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(-0.2, 0, 0)), b.halfShape.get());
    b.compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0.2, 0, 0)), b.halfShape.get());
    toolShape = b.compound.get();
  }
  b.tool = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, &b.toolMotion, toolShape));
  b.tool->setCollisionFlags(b.tool->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  b.tool->setActivationState(DISABLE_DEACTIVATION);
  m_tool = b.tool.get();
  m_world->world().addRigidBody(m_tool);
  if (thinTool) {
    thintool::ToolOptions options = settings.toolOptions;
    options.swept = options.swept && settings.algorithm == Algorithm::ThinTool;
    // The paper's algorithm as published has no last word, no skin regrowth and no friction
    // (ToolOptions::paper()).
    options.separation.enabled = options.separation.enabled && settings.algorithm == Algorithm::ThinTool;
    if (settings.algorithm == Algorithm::ThinToolPaper) {
      options.skinGrowthSpeed = std::numeric_limits<thintool::Real>::infinity();
      options.response.friction.enabled = false;
    }
    try {
      m_thinTool = &thintool::addTool(m_world->world(), *m_tool, options);
    } catch (...) {
      tearDown();  // the destructor does not run for a constructor that throws
      throw;
    }
  }
}

SoftBallScene::~SoftBallScene() { tearDown(); }

void SoftBallScene::tearDown() {
  if (m_thinTool != nullptr) {
    thintool::removeTool(m_world->world(), *m_tool);
  }
  m_world->world().removeRigidBody(m_tool);
  m_world->removeSoftBody(m_ball);
  delete m_ball;
  m_world->world().removeRigidBody(m_bullet->ground.get());
  m_world.reset();
}

void SoftBallScene::setGravity(const btVector3& gravity) { m_world->setGravity(gravity); }

void SoftBallScene::settle() {
  const int steps = static_cast<int>(std::lround(m_settings.settleSeconds / m_settings.timeStep));
  const btTransform parked(btQuaternion::getIdentity(), atOrigin(0, kParkedHeight, 0));
  for (int i = 0; i < steps; ++i) {
    step(parked);
  }
}

double SoftBallScene::step(const btTransform& toolPose) {
  m_bullet->toolMotion.setWorldTransform(toolPose);
  return step();
}

double SoftBallScene::step() {
  const btScalar dt = btScalar(m_settings.timeStep);
  const auto start = std::chrono::steady_clock::now();
  m_world->world().stepSimulation(dt, m_settings.substeps, dt / btScalar(m_settings.substeps));
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

void SoftBallScene::makeToolDynamic(double mass, const btTransform& pose) {
  m_world->world().removeRigidBody(m_tool);
  btVector3 inertia;
  m_tool->getCollisionShape()->calculateLocalInertia(btScalar(mass), inertia);
  m_tool->setMassProps(btScalar(mass), inertia);
  m_tool->setCollisionFlags(m_tool->getCollisionFlags() & ~btCollisionObject::CF_KINEMATIC_OBJECT);
  m_bullet->toolMotion.setWorldTransform(pose);
  m_tool->setWorldTransform(pose);
  m_tool->setInterpolationWorldTransform(pose);
  m_tool->setLinearVelocity(btVector3(0, 0, 0));
  m_tool->setAngularVelocity(btVector3(0, 0, 0));
  // On a vertical slide, as a tool held by a device arm: a frictionless plate on a dome would
  // otherwise tip or slide off it.
  m_tool->setAngularFactor(0);
  m_tool->setLinearFactor(btVector3(0, 1, 0));
  m_tool->updateInertiaTensor();
  m_world->world().addRigidBody(m_tool);
}

btRigidBody& SoftBallScene::ground() { return *m_bullet->ground; }

btSoftRigidDynamicsWorld& SoftBallScene::world() {
  if (m_world->softRigid() == nullptr) {
    throw std::logic_error(
        "SoftBallScene::world(): the scene is in a btSoftMultiBodyDynamicsWorld; use dynamicsWorld()");
  }
  return *m_world->softRigid();
}

btSoftBodyWorldInfo& SoftBallScene::worldInfo() { return m_world->worldInfo(); }

ToolBox SoftBallScene::toolBox() const {
  ToolBox box;
  const btTransform& t = m_tool->getWorldTransform();
  for (int i = 0; i < 3; ++i) {
    const btVector3& row = t.getBasis()[i];
    box.rotationRows[i] = {row.x(), row.y(), row.z()};
  }
  box.origin = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()};
  const btVector3 half = m_bullet->toolShape->getHalfExtentsWithMargin();
  box.halfExtents = {half.x(), half.y(), half.z()};
  return box;
}

btVector3 SoftBallScene::atOrigin(double x, double y, double z) const {
  const std::array<double, 3>& o = m_settings.origin;
  return btVector3(btScalar(o[0] + x), btScalar(o[1] + y), btScalar(o[2] + z));
}

btVector3 SoftBallScene::aboveBall(double y) const {
  return btVector3(btScalar(m_centreX), btScalar(y), btScalar(m_centreZ));
}

void SoftBallScene::centreOverBall() {
  const Vec3 centre = meanNodePosition(*m_ball);
  m_centreX = centre.x;
  m_centreZ = centre.z;
}

double SoftBallScene::softMargin() const { return m_ball->getCollisionShape()->getMargin(); }

double SoftBallScene::ballTop() const {
  double top = -1e30;
  for (int i = 0; i < m_ball->m_nodes.size(); ++i) {
    top = std::max(top, double(m_ball->m_nodes[i].m_x.y()));
  }
  return top;
}

double SoftBallScene::ballMeanHeight() const { return meanHeight(*m_ball); }

double SoftBallScene::pressStartHeight() const {
  constexpr double kStartClearance = 0.1;  // m between the tool's underside and the soft margin
  return ballTop() + softMargin() + kStartClearance + toolBox().halfExtents.y;
}


Vec3 meanNodePosition(const btSoftBody& body) {
  Vec3 sum;
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    const btVector3& x = body.m_nodes[i].m_x;
    sum += Vec3{double(x.x()), double(x.y()), double(x.z())};
  }
  return sum / double(body.m_nodes.size());
}

double meanHeight(const btSoftBody& body) { return meanNodePosition(body).y; }

ToolBox boxAt(const btTransform& pose, const Vec3& halfExtents) {
  ToolBox box;
  const btMatrix3x3& basis = pose.getBasis();
  for (int i = 0; i < 3; ++i) box.rotationRows[i] = {basis[i].x(), basis[i].y(), basis[i].z()};
  box.origin = {pose.getOrigin().x(), pose.getOrigin().y(), pose.getOrigin().z()};
  box.halfExtents = {halfExtents.x, halfExtents.y, halfExtents.z};
  return box;
}

std::vector<Point> nodePositions(const btSoftBody& ball) {
  std::vector<Point> points(ball.m_nodes.size());
  for (int i = 0; i < ball.m_nodes.size(); ++i) {
    const btVector3& x = ball.m_nodes[i].m_x;
    points[i] = {x.x(), x.y(), x.z()};
  }
  return points;
}

std::vector<std::array<int, 3>> faceIndices(const btSoftBody& ball) {
  std::vector<std::array<int, 3>> faces(ball.m_faces.size());
  for (int i = 0; i < ball.m_faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      faces[i][k] = static_cast<int>(ball.m_faces[i].m_n[k] - &ball.m_nodes[0]);
    }
  }
  return faces;
}


PressResult runPress(const PressSettings& settings) {
  SoftBallScene scene(settings.scene);
  scene.settle();
  const double dt = settings.scene.timeStep;
  const double startHeight = scene.pressStartHeight();
  const double targetHeight = scene.ballMeanHeight();
  const int moveSteps = static_cast<int>(std::ceil((startHeight - targetHeight) / (settings.speed * dt)));
  const int holdSteps = static_cast<int>(std::lround(settings.holdSeconds / dt));

  btTransform pose(btQuaternion::getIdentity(), scene.aboveBall(startHeight));
  scene.step(pose);  // place the tool at its start
  const std::vector<std::array<int, 3>> faces = faceIndices(scene.ball());
  BoxGroundTruth truth;
  truth.start(scene.toolBox(), nodePositions(scene.ball()), faces);

  PressResult result;
  double wallMicroseconds = 0;
  double toolMicroseconds = 0;
  for (int i = 1; i <= moveSteps + holdSteps; ++i) {
    const double height = std::max(targetHeight, startHeight - settings.speed * dt * std::min(i, moveSteps));
    pose.setOrigin(scene.aboveBall(height));
    result.stepMicroseconds.push_back(scene.step(pose));
    wallMicroseconds += result.stepMicroseconds.back();
    truth.update(scene.toolBox(), nodePositions(scene.ball()), faces);
    if (thintool::Tool* tool = scene.tool()) {
      const thintool::ToolStepReport& report = tool->report();
      const thintool::ToolDiagnostics& d = report.diagnostics;
      toolMicroseconds += d.detectionMicroseconds + d.responseMicroseconds + d.lastWord.microseconds;
      result.maxContacts = std::max(result.maxContacts, int(d.detection.colliding));
      result.excludedByCheck1 += d.detection.excludedByCheck1;
      result.excludedByCheck2 += d.detection.excludedByCheck2;
      result.maxRemainingPenetration = std::max(result.maxRemainingPenetration, d.maxRemainingPenetration);
      result.lastWordMoves += long(d.lastWord.counts.nodesMoved) + long(d.lastWord.counts.facesMoved);
      result.deformableNodeContacts += long(d.deformableNodeContacts);
    }
  }
  result.steps = moveSteps + holdSteps;
  result.microsecondsPerStep = wallMicroseconds / result.steps;
  result.toolMicrosecondsPerStep = toolMicroseconds / result.steps;
  result.metrics = truth.metrics();
  return result;
}

RunMetrics runTrajectory(SoftBallScene& scene, int steps, const std::function<btTransform(int)>& poseAt) {
  scene.step(poseAt(0));
  const std::vector<std::array<int, 3>> faces = faceIndices(scene.ball());
  BoxGroundTruth truth;
  truth.start(scene.toolBox(), nodePositions(scene.ball()), faces);
  for (int i = 1; i <= steps; ++i) {
    scene.step(poseAt(i));
    truth.update(scene.toolBox(), nodePositions(scene.ball()), faces);
  }
  return truth.metrics();
}

}  // namespace thintool::scenes
