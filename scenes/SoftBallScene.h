// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The paper's first scene and the team's baseline (shared/notes/baseline.md): a kinematic thin
/// tool pressed into a 128-face soft ball resting on the ground, run with stock Bullet or with
/// ThinTool. Shared by the main job, the tests and the benchmarks; not part of the library.

#include "Metrics.h"
#include "WorldKind.h"

#include <thintool/thintool.h>

#include <LinearMath/btTransform.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

class btDiscreteDynamicsWorld;
class btSoftRigidDynamicsWorld;
class btSoftBody;
struct btSoftBodyWorldInfo;
class btRigidBody;
class btCollisionShape;

namespace thintool::scenes {

/// Who handles the tool–ball contact, with the soft settings of baseline.md's variants.
enum class Algorithm {
  StockA,    ///< stock defaults: margin 0.25, kKHR 0.1, 1 position iteration, SDF voxel 0.25
  StockB,    ///< A tuned: kKHR 1, 10 position iterations
  StockE,    ///< B with a realistic skin: margin 0.05, SDF voxel 0.02
  ThinToolPaper,  ///< E's soft settings, the tool registered with the paper's algorithm as published (ToolOptions::paper())
  ThinTool,       ///< E's soft settings, the tool registered with ThinTool's defaults (swept detection)
};
const char* algorithmName(Algorithm algorithm);

/// The soft-body settings baseline.md's variants differ in; ThinTool's runs use E's.
struct SoftVariant {
  double margin;           ///< m, the soft body's collision margin
  double kKHR;             ///< kinetic contact hardness
  int positionIterations;
  double voxel;            ///< m, the sparse SDF's voxel
};
SoftVariant softVariantOf(Algorithm algorithm);

enum class ToolShape {
  Plate,       ///< 0.8 × 0.02 × 0.8 m, thin along y
  Needle,      ///< a bar 1.0 × 0.02 × 0.02 m along x
  SplitPlate,  ///< the plate as a btCompoundShape of two 0.4 m halves side by side
};
const char* toolShapeName(ToolShape shape);

struct SceneSettings {
  Algorithm algorithm = Algorithm::ThinTool;
  ToolShape tool = ToolShape::Plate;
  WorldKind world = WorldKind::SoftRigid;
  double timeStep = 1.0 / 60;  ///< s
  int ballResolution = 63;     ///< btSoftBodyHelpers::CreateEllipsoid's res: 63 gives 128 faces
  /// Joins CreateEllipsoid's res + 3 points by btConvexHullComputer instead of CreateEllipsoid's
  /// hull library, which gives a unit ball no more than about 2,360 faces whatever res asks for
  /// (2,298 for res 2,047); this keeps every point: 2·(res + 1) faces, 65,536 for res 32,767.
  bool exactBallHull = false;
  double settleSeconds = 2;
  int substeps = 1;  ///< internal steps per timeStep: stepSimulation(timeStep, substeps, timeStep / substeps)
  /// Used when algorithm is ThinTool; ThinToolPaper turns swept, separation and skin regrowth off.
  thintool::ToolOptions toolOptions;
  double toolThickness = 0.02;  ///< m, along the tool's y axis (0 makes a tool of zero thickness)
  /// Where the scene is built (m): ground, ball and parked tool are placed relative to it.
  /// Coordinates far from 0 cost float precision.
  std::array<double, 3> origin{0, 0, 0};
};

/// A world with ground, ball and tool, stepped by the caller. The tool is kinematic and follows
/// the pose given to step(), as a haptic device's pose would through a motion state.
class SoftBallScene {
 public:
  explicit SoftBallScene(const SceneSettings& settings);
  ~SoftBallScene();
  SoftBallScene(const SoftBallScene&) = delete;
  SoftBallScene& operator=(const SoftBallScene&) = delete;

  /// Gravity for the world and its soft bodies (SoftWorldOfKind::setGravity), m/s².
  void setGravity(const btVector3& gravity);
  /// Lets the ball settle for settings.settleSeconds with the tool parked far above.
  void settle();
  /// Moves the tool to toolPose and steps once; returns the wall time of stepSimulation (µs).
  double step(const btTransform& toolPose);
  /// Steps once without touching the tool (a dynamic tool moves by itself).
  double step();
  /// Turns the tool into a dynamic body of the given mass (kg), released at pose at rest, free to
  /// move vertically only (a device's slide).
  void makeToolDynamic(double mass, const btTransform& pose);

  /// The world of a WorldKind::SoftRigid scene; throws std::logic_error for the other kinds.
  btSoftRigidDynamicsWorld& world();
  /// The world, of any kind.
  btDiscreteDynamicsWorld& dynamicsWorld() { return m_world->world(); }
  btSoftBodyWorldInfo& worldInfo();
  btSoftBody& ball() { return *m_ball; }
  btRigidBody& toolBody() { return *m_tool; }
  btRigidBody& ground();
  thintool::Tool* tool() { return m_thinTool; }
  const SceneSettings& settings() const { return m_settings; }
  ToolBox toolBox() const;
  double softMargin() const;
  /// Highest and mean node height of the ball (m, world).
  double ballTop() const;
  double ballMeanHeight() const;
  /// Where a press starts (m, world height of the tool's origin): its underside 0.1 m above the
  /// soft margin over the ball's top, as in the team's baseline.
  double pressStartHeight() const;
  /// The world position of a point given relative to settings().origin.
  btVector3 atOrigin(double x, double y, double z) const;
  /// The point at world height y on the vertical line through the ball's centre: where it was
  /// built, or where centreOverBall last found it.
  btVector3 aboveBall(double y) const;
  /// Moves aboveBall's line to the ball's nodes' mean as they lie now. A pressure ball on the
  /// ground can drift while it settles (in the 1/10,000 s stress cases, Bullet's float build); a
  /// press meant to come from above would otherwise meet its side.
  void centreOverBall();

 private:
  void tearDown();

  SceneSettings m_settings;
  double m_centreX, m_centreZ;  // aboveBall's line (m, world)
  struct Bullet;
  std::unique_ptr<Bullet> m_bullet;
  std::unique_ptr<SoftWorldOfKind> m_world;
  btSoftBody* m_ball = nullptr;
  btRigidBody* m_tool = nullptr;
  thintool::Tool* m_thinTool = nullptr;
};

/// The baseline run: the tool starts 0.1 m above the soft margin over the ball's top, moves
/// straight down at `speed` to the ball's mean node height, then holds for `holdSeconds`.
struct PressSettings {
  SceneSettings scene;
  double speed = 1;  ///< m/s
  double holdSeconds = 0.25;
};

struct PressResult {
  RunMetrics metrics;
  int steps = 0;                        ///< steps while moving and holding
  double microsecondsPerStep = 0;       ///< mean stepSimulation wall time over those steps
  double toolMicrosecondsPerStep = 0;   ///< ThinTool's own share (detection, response, last word)
  std::vector<double> stepMicroseconds;  ///< each of those steps' stepSimulation wall time
  int maxContacts = 0;                  ///< ThinTool contacts in one step
  long excludedByCheck1 = 0;            ///< summed over the steps
  long excludedByCheck2 = 0;
  double maxRemainingPenetration = 0;   ///< ThinTool's own measure, for comparison with metrics
  long lastWordMoves = 0;               ///< node and face moves of ThinTool's last word, summed over the steps
  long deformableNodeContacts = 0;      ///< node contacts ThinTool gave Bullet's deformable solve, summed
};

PressResult runPress(const PressSettings& settings);

/// CreateEllipsoid's ball with every one of its res + 3 points a node: 2·res + 2 faces (63: 128,
/// 2,047: 4,096, 32,767: 65,536). CreateEllipsoid's hull drops points from res 255 on and stops
/// near 2,400 faces. The caller owns the body.
btSoftBody* createExactHullEllipsoid(btSoftBodyWorldInfo& info, const btVector3& centre, const btVector3& radii,
                                     int res);

/// The ball's node positions and face indices, for the metrics.
std::vector<Point> nodePositions(const btSoftBody& ball);
std::vector<std::array<int, 3>> faceIndices(const btSoftBody& ball);
/// A soft body's mean node position (m, world).
Vec3 meanNodePosition(const btSoftBody& body);
/// A soft body's mean node height (m): where a grasp lifted it to.
double meanHeight(const btSoftBody& body);
/// A box of the given half extents (m) at pose, for the metrics.
ToolBox boxAt(const btTransform& pose, const Vec3& halfExtents);

/// Drives the tool of a settled scene through poseAt(step) for steps steps, tracking the ball's
/// nodes against the tool; the ground truth starts at pose 0.
RunMetrics runTrajectory(SoftBallScene& scene, int steps, const std::function<btTransform(int)>& poseAt);

}  // namespace thintool::scenes
