// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "Runner.h"

#include <SoftBallScene.h>
#include <TetraBlock.h>

#include <thintool/bullet/Convert.h>
#include <thintool/core/Error.h>
#include <thintool/thintool.h>

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace thintool::eval {

namespace {

constexpr double kParkedAbove = 50;  // m: tools wait this far above their start while the body settles

scenes::Algorithm baselineAlgorithmOf(AlgorithmKind kind) {
  switch (kind) {
    case AlgorithmKind::StockA: return scenes::Algorithm::StockA;
    case AlgorithmKind::StockB: return scenes::Algorithm::StockB;
    case AlgorithmKind::StockE: return scenes::Algorithm::StockE;
    case AlgorithmKind::RayOnly:
    case AlgorithmKind::Paper: return scenes::Algorithm::ThinToolPaper;
    case AlgorithmKind::Swept:
    case AlgorithmKind::Discrete: break;
  }
  return scenes::Algorithm::ThinTool;
}

bool isIdentity(const Pose& pose) {
  const Pose identity;
  return pose.translation == identity.translation && pose.rotation.row[0] == identity.rotation.row[0] &&
         pose.rotation.row[1] == identity.rotation.row[1] && pose.rotation.row[2] == identity.rotation.row[2];
}

// Everything Bullet needs kept alive, torn down in the right order by the destructor.
struct World {
  std::unique_ptr<btCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  btDbvtBroadphase broadphase;
  std::unique_ptr<btSoftBodySolver> softSolver;
  std::unique_ptr<scenes::SoftWorldOfKind> world;
  btBoxShape groundShape{btVector3(20, 1, 20)};
  btDefaultMotionState groundMotion{btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0))};
  std::unique_ptr<btRigidBody> ground;
  btSoftBody* soft = nullptr;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motions;
  std::vector<std::unique_ptr<btRigidBody>> tools;
  std::vector<Tool*> thinTools;

  ~World() {
    for (std::size_t i = 0; i < tools.size(); ++i) {
      if (thinTools[i] != nullptr) removeTool(world->world(), *tools[i]);
      world->world().removeRigidBody(tools[i].get());
    }
    if (soft != nullptr) {
      world->removeSoftBody(soft);
      delete soft;
    }
    if (ground) world->world().removeRigidBody(ground.get());
    world.reset();
  }
};

btSoftBody* makeSoftBody(const SceneSpec& scene, btSoftBodyWorldInfo& info) {
  const SoftBodySpec& soft = scene.soft;
  switch (soft.mesh) {
    case SoftBodySpec::Mesh::Ellipsoid:
      if (soft.exactHull) {
        return scenes::createExactHullEllipsoid(info, toBt(soft.centre), toBt(soft.radius), soft.resolution);
      }
      return btSoftBodyHelpers::CreateEllipsoid(info, toBt(soft.centre), toBt(soft.radius), soft.resolution);
    case SoftBodySpec::Mesh::Obj: {
      std::vector<btScalar> coordinates;
      for (const Vec3& v : soft.objMesh.vertices) {
        const Vec3 p = v * soft.scale + soft.centre;
        coordinates.insert(coordinates.end(), {btScalar(p.x), btScalar(p.y), btScalar(p.z)});
      }
      std::vector<int> indices;
      for (const Triangle& t : soft.objMesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
      return btSoftBodyHelpers::CreateFromTriMesh(info, coordinates.data(), indices.data(),
                                                  int(soft.objMesh.triangles.size()));
    }
    case SoftBodySpec::Mesh::Tetra:
      return scenes::createTetraBlock(info, soft.centre, Vec3{soft.sheetSize, soft.sheetSize, soft.sheetSize},
                                      {soft.tetraCells, soft.tetraCells, soft.tetraCells});
    case SoftBodySpec::Mesh::Sheet:
      break;
  }
  const double h = soft.sheetSize / 2;
  const Vec3& c = soft.centre;
  return btSoftBodyHelpers::CreatePatch(info, toBt(c + Vec3{-h, 0, -h}), toBt(c + Vec3{h, 0, -h}),
                                        toBt(c + Vec3{-h, 0, h}), toBt(c + Vec3{h, 0, h}),
                                        soft.nodesPerSide, soft.nodesPerSide, soft.pinnedCorners ? 1 + 2 + 4 + 8 : 0,
                                        true);
}

btCollisionShape* makePieceShape(const ToolPieceSpec& piece, World& w) {
  if (piece.kind == ToolPieceSpec::Kind::Box) {
    w.shapes.push_back(std::make_unique<btBoxShape>(toBt(piece.halfExtents)));
  } else {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& v : piece.hull.vertices) hull->addPoint(toBt(v), false);
    hull->recalcLocalAabb();
    w.shapes.push_back(std::move(hull));
  }
  w.shapes.back()->setMargin(btScalar(0.001));
  return w.shapes.back().get();
}

btCollisionShape* makeToolShape(const ToolSpec& tool, World& w) {
  if (tool.pieces.size() == 1 && isIdentity(tool.pieces[0].offset)) return makePieceShape(tool.pieces[0], w);
  auto compound = std::make_unique<btCompoundShape>();
  for (const ToolPieceSpec& piece : tool.pieces) compound->addChildShape(toTransform(piece.offset), makePieceShape(piece, w));
  w.shapes.push_back(std::move(compound));
  return w.shapes.back().get();
}

ToolOptions optionsFor(const SceneSpec& scene, const ToolSpec& tool) {
  ToolOptions options;
  if (scene.algorithm == AlgorithmKind::Paper) options = ToolOptions::paper();
  if (scene.algorithm == AlgorithmKind::RayOnly) options = ToolOptions::rayOnly();
  if (scene.algorithm == AlgorithmKind::Discrete) options.swept = false;
  options.name = tool.name;
  options.force.enabled = scene.force;
  if (scene.friction.has_value()) {
    options.response.friction.enabled = *scene.friction;
    options.bullet.frictionFromBodies = scene.frictionFromBodies;
  }
  options.separation.enabled = options.separation.enabled && scene.lastWord;
  options.bullet.holdInSolver = options.bullet.holdInSolver && scene.holds;
  if (scene.holdPlaneReach.has_value()) options.bullet.holdPlaneReach = Real(*scene.holdPlaneReach);
  options.bullet.scanFaces = scene.scanFaces;
  options.bullet.deformableNodeContacts = scene.deformableNodeContacts;
  options.sweptFollowsArc = scene.followArc;
  options.energyGuard.enabled = options.energyGuard.enabled && scene.energyGuard;
  options.energyGuard.boundForcesNextStep = options.energyGuard.boundForcesNextStep && scene.boundForces;
  return options;
}

// The narrowest extent of a convex solid across any of its faces' normals: a box's thinnest side.
double narrowestWidth(const SolidDistance& solid) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const Vec3& normal : solid.faceNormals()) {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const Vec3& v : solid.solid().vertices) {
      low = std::min(low, double(dot(normal, v)));
      high = std::max(high, double(dot(normal, v)));
    }
    narrowest = std::min(narrowest, high - low);
  }
  return narrowest;
}

// The angle (radians) of the rotation from a to b.
double turnAngle(const Mat3& a, const Mat3& b) {
  const double trace = dot(a.row[0], b.row[0]) + dot(a.row[1], b.row[1]) + dot(a.row[2], b.row[2]);
  return std::acos(std::clamp((trace - 1) / 2, -1.0, 1.0));
}

// A coordinate planned against a box (centre, half extent) moved onto another: stretched inside
// it, shifted outside it (TrajectorySpec::plannedBodyBox).
double mapOntoBox(double value, double plannedCentre, double plannedHalf, double centre, double half) {
  const double offset = value - plannedCentre;
  if (plannedHalf > 0 && std::abs(offset) <= plannedHalf) return centre + offset * (half / plannedHalf);
  return centre + offset + (offset < 0 ? -1 : 1) * (half - plannedHalf);
}

// The velocity a dynamic tool is launched with: its trajectory's first segment's.
Vec3 launchVelocity(const TrajectorySpec& trajectory) {
  if (trajectory.kind == TrajectorySpec::Kind::ConstantVelocity) return trajectory.direction * trajectory.speed;
  const std::vector<TrajectorySpec::Waypoint>& points = trajectory.waypoints;
  if (points.size() < 2 || !(points[1].time > points[0].time)) return {};
  return (points[1].position - points[0].position) / (points[1].time - points[0].time);
}

std::vector<Vec3> nodesOf(const btSoftBody& soft) {
  std::vector<Vec3> nodes(soft.m_nodes.size());
  for (int i = 0; i < soft.m_nodes.size(); ++i) {
    const btVector3& x = soft.m_nodes[i].m_x;
    nodes[i] = {x.x(), x.y(), x.z()};
  }
  return nodes;
}

// The fastest node between two snapshots of the body, a step apart (m/s); a node that is not
// finite adds nothing (the finiteness check reports it).
double fastestNodeSpeed(const std::vector<Vec3>& before, const std::vector<Vec3>& after, double timeStep) {
  double fastest = 0;
  for (std::size_t n = 0; n < after.size(); ++n) fastest = std::max(fastest, length(after[n] - before[n]) / timeStep);
  return fastest;
}

// Cuts the slit (SoftBodySpec::Cut) through the body as it is now; returns how many links it cut.
int cutSheet(btSoftBody& soft, const SoftBodySpec::Cut& cut) {
  const Vec3 across = normalizedOrZero(cross(cut.direction, Vec3{0, 1, 0}));
  // The links to cut, by their nodes' indices (each cut appends nodes and links), and where along
  // each the plane crosses it.
  struct Crossing {
    int from, to;
    double share;
  };
  std::vector<Crossing> crossings;
  for (int i = 0; i < soft.m_links.size(); ++i) {
    const btSoftBody::Link& link = soft.m_links[i];
    const Vec3 a = toVec3(link.m_n[0]->m_x);
    const Vec3 b = toVec3(link.m_n[1]->m_x);
    const double da = dot(a - cut.point, across);
    const double db = dot(b - cut.point, across);
    if (!(da * db < 0)) continue;
    const double share = da / (da - db);
    const Vec3 crossing = a + (b - a) * share;
    if (!(std::abs(dot(crossing - cut.point, cut.direction)) <= cut.halfLength)) continue;
    crossings.push_back({int(link.m_n[0] - &soft.m_nodes[0]), int(link.m_n[1] - &soft.m_nodes[0]), share});
  }
  int count = 0;
  for (const Crossing& c : crossings) count += soft.cutLink(c.from, c.to, btScalar(c.share)) ? 1 : 0;
  return count;
}

}  // namespace

RunResult runScene(const SceneSpec& scene, const RunOptions& options) {
  const bool stock = isStock(scene.algorithm);
  const scenes::SoftVariant variant = scenes::softVariantOf(baselineAlgorithmOf(scene.algorithm));

  World w;
  if (stock) {
    w.configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
    w.softSolver = scenes::softSolverFor(options.world, nullptr);
  } else {
    auto configuration = std::make_unique<CollisionConfiguration>();
    w.softSolver = scenes::softSolverFor(options.world, configuration.get());
    w.configuration = std::move(configuration);
  }
  w.dispatcher = std::make_unique<btCollisionDispatcher>(w.configuration.get());
  w.world = std::make_unique<scenes::SoftWorldOfKind>(options.world, *w.dispatcher, w.broadphase, *w.configuration,
                                                      *w.softSolver);
  btDiscreteDynamicsWorld& world = w.world->world();
  world.setGravity(toBt(scene.gravity));
  btSoftBodyWorldInfo& info = w.world->worldInfo();
  info.m_gravity = world.getGravity();
  info.m_sparsesdf.setDefaultVoxelsz(btScalar(variant.voxel));
  info.m_sparsesdf.Reset();
  if (scene.ground) {
    w.ground = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, &w.groundMotion, &w.groundShape));
    world.addRigidBody(w.ground.get());
  }

  w.soft = makeSoftBody(scene, info);
  btSoftBody& soft = *w.soft;
  const double substep = scene.timeStep / scene.substeps;
  soft.m_materials[0]->m_kLST = btScalar(scene.soft.linearStiffness);
  soft.m_cfg.kDF = btScalar(scene.soft.friction);
  soft.m_cfg.kPR = btScalar(scene.soft.pressure);
  soft.m_cfg.kKHR = btScalar(variant.kKHR);
  soft.m_cfg.piterations = scene.soft.positionIterations.value_or(variant.positionIterations);
  soft.m_cfg.kDP = btScalar(1 - std::pow(1 - scene.soft.damping, 60 * substep));
  soft.setTotalMass(btScalar(scene.soft.mass));
  if (scene.soft.poseMatching > 0) {
    soft.m_cfg.kMT = btScalar(scene.soft.poseMatching);
    soft.setPose(false, true);
  }
  const double softMargin = scene.soft.margin.value_or(variant.margin);
  soft.getCollisionShape()->setMargin(btScalar(softMargin));
  if (options.world == scenes::WorldKind::Deformable) {
    w.world->addSoftBody(w.soft, scenes::deformableSpringFor(soft, scene.soft.linearStiffness, substep));
  } else {
    w.world->addSoftBody(w.soft);
  }

  std::vector<GroundTruthPiece> pieces;
  std::vector<double> toolReach;  // m, the farthest corner of each tool's pieces from its origin
  std::vector<double> toolThickness;  // m, the narrowest width of each tool's thinnest piece
  for (std::size_t t = 0; t < scene.tools.size(); ++t) {
    const ToolSpec& tool = scene.tools[t];
    const bool dynamic = tool.mass > 0;
    Pose parked = poseAt(tool.trajectory, 0);
    parked.translation.y += kParkedAbove;
    w.motions.push_back(std::make_unique<btDefaultMotionState>(toTransform(parked)));
    btCollisionShape* shape = makeToolShape(tool, w);
    btVector3 inertia(0, 0, 0);
    if (dynamic) shape->calculateLocalInertia(btScalar(tool.mass), inertia);
    auto body = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(
        btScalar(dynamic ? tool.mass : 0), w.motions.back().get(), shape, inertia));
    if (!dynamic) body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(body.get());
    if (dynamic) body->setGravity(btVector3(0, 0, 0));  // addRigidBody gave it the world's
    w.tools.push_back(std::move(body));
    w.thinTools.push_back(stock ? nullptr : &addTool(world, *w.tools.back(), optionsFor(scene, tool)));
    double reach = 0;
    double thickness = std::numeric_limits<double>::infinity();
    for (const ToolPieceSpec& piece : tool.pieces) {
      pieces.push_back({SolidDistance(solidOf(piece)), piece.offset, int(t), !dynamic});
      for (const Vec3& v : solidOf(piece).vertices) reach = std::max(reach, length(piece.offset.apply(v)));
      thickness = std::min(thickness, narrowestWidth(pieces.back().solid));
    }
    toolReach.push_back(reach);
    toolThickness.push_back(thickness);
  }

  const btScalar dt = btScalar(scene.timeStep);
  auto stepWorld = [&] {
    const auto start = std::chrono::steady_clock::now();
    world.stepSimulation(dt, scene.substeps, dt / btScalar(scene.substeps));
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  };
  const int settleSteps = int(std::lround(scene.settleSeconds / scene.timeStep));
  double settleNodeSpeed = 0;
  std::vector<Vec3> settling = nodesOf(soft);
  for (int i = 0; i < settleSteps; ++i) {
    stepWorld();
    std::vector<Vec3> settled = nodesOf(soft);
    settleNodeSpeed = std::max(settleNodeSpeed, fastestNodeSpeed(settling, settled, scene.timeStep));
    settling = std::move(settled);
  }
  double softBottom = std::numeric_limits<double>::max();
  double softTop = -softBottom;
  for (int i = 0; i < soft.m_nodes.size(); ++i) {
    softBottom = std::min(softBottom, double(soft.m_nodes[i].m_x.y()));
    softTop = std::max(softTop, double(soft.m_nodes[i].m_x.y()));
  }
  Vec3 softLow = Vec3{1, 1, 1} * std::numeric_limits<double>::max();
  Vec3 softHigh = -softLow;
  for (const Vec3& node : nodesOf(soft)) {
    softLow = componentMin(softLow, node);
    softHigh = componentMax(softHigh, node);
  }
  if (options.settled) {
    options.settled(softBottom, softTop);
  }

  // Trajectories that start relative to the settled body.
  std::vector<TrajectorySpec> trajectories;
  for (const ToolSpec& tool : scene.tools) {
    TrajectorySpec trajectory = tool.trajectory;
    if (trajectory.startClearance) {
      const Pose start = poseAt(trajectory, 0);
      double lowest = std::numeric_limits<double>::max();
      for (const ToolPieceSpec& piece : tool.pieces) {
        for (const Vec3& v : solidOf(piece).vertices) lowest = std::min(lowest, start.apply(piece.offset.apply(v)).y);
      }
      trajectory.start.y += softTop + softMargin + *trajectory.startClearance - lowest;
    }
    if (trajectory.plannedBodyBox) {
      const Vec3& plannedLow = (*trajectory.plannedBodyBox)[0];
      const Vec3& plannedHigh = (*trajectory.plannedBodyBox)[1];
      for (TrajectorySpec::Waypoint& point : trajectory.waypoints) {
        for (int axis = 0; axis < 3; ++axis) {
          point.position[axis] = mapOntoBox(point.position[axis], (plannedLow[axis] + plannedHigh[axis]) / 2,
                                            (plannedHigh[axis] - plannedLow[axis]) / 2,
                                            (softLow[axis] + softHigh[axis]) / 2, (softHigh[axis] - softLow[axis]) / 2);
        }
      }
    }
    trajectories.push_back(trajectory);
  }

  // Out of the parking place: a jump, not a motion for swept detection to sweep. A dynamic body is
  // placed by hand at rest for the step of the jump, and launched after it: launched with it, it
  // flew a step's worth unswept, and a fast needle began the judged steps inside the body.
  std::vector<Pose> toolPoses;
  const auto placeDynamic = [&](std::size_t t, const Pose& pose, const Vec3& velocity) {
    btRigidBody& body = *w.tools[t];
    body.setWorldTransform(toTransform(pose));
    body.setInterpolationWorldTransform(toTransform(pose));
    body.setLinearVelocity(toBt(velocity));
    body.setAngularVelocity(btVector3(0, 0, 0));
    body.setInterpolationLinearVelocity(body.getLinearVelocity());
    body.setInterpolationAngularVelocity(btVector3(0, 0, 0));
    body.clearForces();
  };
  for (std::size_t t = 0; t < scene.tools.size(); ++t) {
    const Pose start = poseAt(trajectories[t], 0);
    w.motions[t]->setWorldTransform(toTransform(start));
    if (scene.tools[t].mass > 0) placeDynamic(t, start, {});
    if (w.thinTools[t] != nullptr) w.thinTools[t]->resetMotion();
    toolPoses.push_back(start);
  }
  stepWorld();
  // Launched along the path mapped onto the settled body, at the speed it was planned with: the
  // mapping stretches the path with the body, and a ball that settled 3.7 m tall launched a needle
  // planned at 30 m/s at 176 m/s, past the generator's 50 m/s (generated seed 9098).
  for (std::size_t t = 0; t < scene.tools.size(); ++t) {
    if (!(scene.tools[t].mass > 0)) continue;
    const Vec3 planned = launchVelocity(scene.tools[t].trajectory);
    placeDynamic(t, toPose(w.tools[t]->getWorldTransform()),
                 normalizedOrZero(launchVelocity(trajectories[t])) * length(planned));
  }

  RunResult result;
  result.scene = scene.name;
  result.algorithm = scene.algorithm;
  result.timeStep = scene.timeStep;
  result.softNodes = soft.m_nodes.size();
  result.softFaces = soft.m_faces.size();
  result.settleNodeSpeed = settleNodeSpeed;
  for (Tool* tool : w.thinTools) result.toolNodes += tool != nullptr ? int(tool->nodeCount()) : 0;

  std::vector<Triangle> faces = scenes::faceIndices(soft);
  GroundTruth truth(std::move(pieces), scene.soft.mesh != SoftBodySpec::Mesh::Sheet);
  // The dynamic tools have moved in the step above: the ground truth starts from where they are.
  for (std::size_t t = 0; t < scene.tools.size(); ++t) {
    if (scene.tools[t].mass > 0) toolPoses[t] = toPose(w.tools[t]->getWorldTransform());
  }
  std::vector<Vec3> previousNodes = nodesOf(soft);
  std::vector<int> pinned;
  for (int n = 0; n < soft.m_nodes.size(); ++n) {
    if (soft.m_nodes[n].m_im == 0) pinned.push_back(n);
  }
  truth.start(toolPoses, previousNodes, faces, std::move(pinned));

  const int steps = std::max(1, int(std::lround(scene.duration / scene.timeStep)));
  double wall = 0;
  double toolTime = 0;
  bool cut = false;
  for (int i = 1; i <= steps; ++i) {
    const double time = i * scene.timeStep;
    if (scene.soft.cut && !cut && time > scene.soft.cut->time) {
      result.linksCut = cutSheet(soft, *scene.soft.cut);
      faces = scenes::faceIndices(soft);
      previousNodes = nodesOf(soft);
      truth.addNodes(previousNodes);
      cut = true;
    }
    const std::vector<Pose> posesBefore = toolPoses;
    for (std::size_t t = 0; t < scene.tools.size(); ++t) {
      if (scene.tools[t].mass > 0) continue;  // dynamic: moves by itself
      toolPoses[t] = poseAt(trajectories[t], time);
      w.motions[t]->setWorldTransform(toTransform(toolPoses[t]));
    }
    StepSample sample;
    sample.time = time;
    sample.stepMicroseconds = stepWorld();
    for (Tool* tool : w.thinTools) {
      if (tool == nullptr) continue;
      const ToolStepReport& report = tool->report();
      sample.toolMicroseconds += report.diagnostics.detectionMicroseconds + report.diagnostics.responseMicroseconds +
                                 report.diagnostics.lastWord.microseconds;
      sample.force += report.contactForce.force;
      result.nonFiniteWrites += double(report.diagnostics.nonFiniteWrites);
    }
    const std::vector<Vec3> nodes = nodesOf(soft);
    for (const Vec3& node : nodes) result.finite = result.finite && isFinite(node);
    if (!result.finite) break;
    for (std::size_t t = 0; t < scene.tools.size(); ++t) {
      toolPoses[t] = toPose(w.tools[t]->getWorldTransform());
      const double speed = (length(toolPoses[t].translation - posesBefore[t].translation) +
                            turnAngle(posesBefore[t].rotation, toolPoses[t].rotation) * toolReach[t]) /
                           scene.timeStep;
      result.peakToolSpeed = std::max(result.peakToolSpeed, speed);
      result.peakToolStepOverThickness =
          std::max(result.peakToolStepOverThickness, speed * scene.timeStep / toolThickness[t]);
    }
    sample.nodeSpeed = fastestNodeSpeed(previousNodes, nodes, scene.timeStep);
    result.peakNodeSpeed = std::max(result.peakNodeSpeed, sample.nodeSpeed);
    previousNodes = nodes;
    const GroundTruthStep& step = truth.update(toolPoses, nodes, faces);
    sample.crossings = step.crossings;
    sample.toolInside = step.toolInside;
    sample.selfIntersecting = step.selfIntersecting;
    sample.pinnedReached = step.pinnedReached;
    sample.maxPenetration = step.maxPenetration;
    sample.piercedFaces = step.piercedFaces;
    wall += sample.stepMicroseconds;
    toolTime += sample.toolMicroseconds;
    result.peakForce = std::max(result.peakForce, length(sample.force));
    result.samples.push_back(sample);
    if (options.progress) options.progress(i, steps);
  }
  result.truth = truth.run();
  const double measured = double(std::max<std::size_t>(1, result.samples.size()));
  result.microsecondsPerStep = wall / measured;
  result.toolMicrosecondsPerStep = toolTime / measured;
  return result;
}

double forceError(const RunResult& run, const RunResult& reference) {
  if (run.peakForce == 0 || reference.peakForce == 0 || run.samples.empty()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double sumSquared = 0;
  std::size_t j = 0;
  for (const StepSample& r : reference.samples) {
    while (j + 1 < run.samples.size() && run.samples[j + 1].time <= r.time) ++j;
    Vec3 force = run.samples[j].force;
    if (j + 1 < run.samples.size() && r.time > run.samples[j].time) {
      const StepSample& a = run.samples[j];
      const StepSample& b = run.samples[j + 1];
      const double s = std::min(1.0, (r.time - a.time) / (b.time - a.time));
      force = a.force + (b.force - a.force) * s;
    }
    sumSquared += lengthSquared(force - r.force);
  }
  return std::sqrt(sumSquared / double(reference.samples.size())) / reference.peakForce;
}

}  // namespace thintool::eval
