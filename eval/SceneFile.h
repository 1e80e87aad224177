// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The evaluation suite's scene files: JSON naming a soft body, the tools and their trajectories,
/// the step and which algorithm handles the tool–tissue contact. eval/scenes/README.md documents
/// every field with its unit and default; loadScene() reads a file into plain data and reports the
/// first problem as "file:line:column: field: what was expected". Unknown fields are errors, so a
/// typo never silently falls back to a default.

#include "GroundTruth.h"
#include "ObjMesh.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace thintool::eval {

/// Who handles the tool–tissue contact. The stock variants are baseline.md's; ThinTool's run on
/// variant E's soft settings (realistic skin), as in the main job's tables (docs/results/main-job.md).
enum class AlgorithmKind {
  StockA,    ///< Bullet's defaults: margin 0.25, kKHR 0.1, 1 position iteration, SDF voxel 0.25
  StockB,    ///< A with kKHR 1 and 10 iterations
  StockE,    ///< B with margin 0.05 and voxel 0.02
  RayOnly,   ///< ThinTool: the paper's discrete rays without association or checks (Fig. 7 right)
  Paper,     ///< ThinTool: the paper's full algorithm (discrete)
  Swept,     ///< ThinTool's default: swept detection
  Discrete,  ///< ThinTool's defaults with the paper's discrete detection in place of the swept one
};
/// The name used in scene files and result tables: "stock-A", ..., "swept", "discrete".
const char* algorithmKey(AlgorithmKind kind);
bool isStock(AlgorithmKind kind);

struct SoftBodySpec {
  enum class Mesh { Ellipsoid, Obj, Sheet, Tetra };
  Mesh mesh = Mesh::Ellipsoid;
  // Ellipsoid: Bullet's CreateEllipsoid at `resolution` (63 gives the paper's 128 faces). Its hull
  // drops points from res 255 on and stops near 2,400 faces; exactHull keeps every point as a
  // node: 2·(res + 1) faces, 4,096 for res 2,047 and 65,536 for res 32,767.
  int resolution = 63;
  bool exactHull = false;
  Vec3 centre{0, 1.3, 0};   ///< m (also the OBJ's translation, and the sheet's centre)
  Vec3 radius{1, 1, 1};     ///< m
  // OBJ: a closed surface mesh, scaled then moved to centre.
  std::string objFile;      ///< as written in the file
  double scale = 1;
  TriangleMesh objMesh;     ///< read when the scene is loaded, unscaled
  // Sheet: a square patch in the xz plane, nodesPerSide² nodes, pinned at its four corners.
  double sheetSize = 1;     ///< m, side (also the tetra box's edge)
  int nodesPerSide = 17;
  bool pinnedCorners = true;  ///< false: a free cloth. Not read from scene files (the scene generator sets it)
  /// Sheet: a slit cut through it during the run, as Bullet's demos cut cloth: every link whose
  /// nodes lie either side of the vertical plane along `direction` through `point`, and that
  /// crosses it within halfLength of point, is cut there (btSoftBody::cutLink, which adds two nodes
  /// a link and splits its faces). Not read from scene files (the scene generator sets it).
  struct Cut {
    double time = 0;           ///< s after t = 0, before the step that ends after it
    Vec3 point;                ///< m; its height is not used
    Vec3 direction{1, 0, 0};   ///< along the slit, horizontal, unit
    double halfLength = 0.5;   ///< m
  };
  std::optional<Cut> cut;
  // Tetra: a closed box of tetrahedra, edge sheetSize, resting where centre puts it: tetraCells
  // cubes a side, six tetrahedra each, built by btSoftBodyHelpers::CreateFromTetGenData; its
  // surface is the tetrahedra's outer faces, and its links their edges. Not read from scene files
  // (the scene generator sets it).
  int tetraCells = 3;
  // Material (btSoftBody's): a closed body is held up by pressure.
  double mass = 1;             ///< kg, whole body
  double linearStiffness = 0.5;  ///< kLST, 0..1
  double pressure = 50;        ///< kPR, Pa; 0 for a sheet
  double friction = 0.5;       ///< kDF
  double damping = 0.05;       ///< kDP at a 1/60 s step; other steps get the same damping per second
  /// kMT, 0..1: pose matching, which pulls the body towards its rest shape each step (Bullet's
  /// setPose(false, true), as its demos' pose-matched torus); 0 leaves it off. Not read from scene
  /// files (the scene generator sets it).
  double poseMatching = 0;
  // Solver overrides, not read from scene files (the scene generator sets them): when set, they
  // replace the algorithm variant's values, so every algorithm runs the same soft solver.
  std::optional<int> positionIterations;  ///< piterations
  std::optional<double> margin;           ///< m, the soft body's collision margin
};

/// Rotations are rotation vectors in degrees: the axis scaled by the angle, [0, 0, 30] turning
/// 30° about z.
Pose poseOf(const Vec3& position, const Vec3& rotationDegrees);

struct ToolPieceSpec {
  enum class Kind { Box, Hull };
  Kind kind = Kind::Box;
  Vec3 halfExtents{0.4, 0.01, 0.4};  ///< m
  std::string objFile;               ///< hull: a closed convex OBJ, as written in the file
  double scale = 1;
  ConvexSolid hull;                  ///< read when the scene is loaded, scaled
  Pose offset;                       ///< the piece in the tool's frame (compound tools)
};

struct TrajectorySpec {
  enum class Kind { ConstantVelocity, Waypoints, Csv };
  Kind kind = Kind::ConstantVelocity;
  // Constant velocity: from start, `distance` along `direction` at `speed`, then held.
  Vec3 start{0, 2.5, 0};      ///< m, at t = 0
  Vec3 rotation;              ///< degrees, fixed
  Vec3 direction{0, -1, 0};   ///< unit
  double speed = 1;           ///< m/s
  double distance = 1;        ///< m
  /// When set (m), start.y is replaced, once the soft body has settled, by the height that puts
  /// the tool's lowest point this far above the soft body's top plus its collision margin, so
  /// that every algorithm's soft settings (a 0.25 m margin lifts the ball) start the same way.
  std::optional<double> startClearance;
  struct Waypoint {
    double time = 0;  ///< s
    Vec3 position;    ///< m
    Vec3 rotation;    ///< degrees
  };
  /// Waypoints and CSV rows: poses at increasing times, linear in position and rotation vector
  /// between them, held before the first and after the last.
  std::vector<Waypoint> waypoints;
  std::string csvFile;  ///< columns t,x,y,z[,rx,ry,rz] (s, m, degrees), read into waypoints
  /// Waypoints only, not read from scene files (the scene generator sets it): the soft body's
  /// bounding box (low, high corners, m) as built, against which the waypoints were planned. Once
  /// the body has settled, each waypoint coordinate is mapped piecewise linearly so that this box
  /// lands on the settled body's: stretched inside it, shifted outside it. A start planned clear
  /// of the body stays as clear, and a target in its middle stays there, however the body sagged,
  /// spread or swelled.
  std::optional<std::array<Vec3, 2>> plannedBodyBox;
};

struct ToolSpec {
  std::string name;
  std::vector<ToolPieceSpec> pieces;  ///< one for a box or hull tool, several for a compound
  TrajectorySpec trajectory;
  /// kg. 0: kinematic, driven through the trajectory. More: a dynamic body without gravity, put at
  /// the trajectory's start and launched with its first segment's velocity (direction·speed, or
  /// the first two waypoints' difference over their times), then free. Not read from scene files
  /// (the scene generator sets it).
  double mass = 0;
};

struct SceneSpec {
  std::string name;
  std::string sourcePath;
  double timeStep = 1.0 / 60;  ///< s
  int substeps = 1;
  double settleSeconds = 2;    ///< s before t = 0, tools parked at their first pose
  double duration = 0;         ///< s after t = 0; 0: the last trajectory's end plus holdSeconds
  double holdSeconds = 0.25;   ///< s
  Vec3 gravity{0, -10, 0};     ///< m/s²
  bool ground = true;          ///< a static box whose top is y = 0
  SoftBodySpec soft;
  std::vector<ToolSpec> tools;
  AlgorithmKind algorithm = AlgorithmKind::Swept;
  bool force = false;          ///< ThinTool: the Hunt–Crossley force (force error needs it)
  /// ThinTool's Coulomb friction at the tool. Unset, the library's default (on, each pair's
  /// coefficient from the bodies); true, on, with ThinTool's own coefficients unless
  /// frictionFromBodies; false, off.
  std::optional<bool> friction;
  /// With friction on: each pair's coefficient from the bodies, as stock Bullet's node contact (the
  /// soft body's kDF times the tool's friction, BulletSettings::frictionFromBodies).
  bool frictionFromBodies = false;
  bool lastWord = true;        ///< ThinTool: the last word after the soft solver (ToolOptions::separation); "paper" and "ray-only" never have it
  bool holds = true;           ///< ThinTool: the response's holds in the soft solver (BulletSettings::holdInSolver)
  std::optional<double> holdPlaneReach;  ///< ThinTool: how far the holds reach along their planes (BulletSettings::holdPlaneReach); unset, the library's default
  bool energyGuard = true;     ///< ThinTool: the energy guard after the soft solver (ToolOptions::energyGuard); "paper" and "ray-only" never have it
  bool boundForces = true;     ///< ThinTool: with the energy guard, the bound on the forces in the step after a guarded one (EnergyGuardSettings::boundForcesNextStep)
  bool scanFaces = false;      ///< ThinTool: swept detection reads every soft face instead of walking a face tree (BulletSettings::scanFaces)
  /// ThinTool in the deformable world: its detection gives Bullet's solve the tool's node contacts
  /// (BulletSettings::deformableNodeContacts)
  bool deformableNodeContacts = true;
  bool followArc = false;      ///< ThinTool: swept detection confirms a node's chord on the turning tool's arc (ToolOptions::sweptFollowsArc)
};

/// An override applied to the file's JSON before it is read: path=value, the path in dots and
/// [index] (tools[0].trajectory.velocity), the value JSON or, failing that, a bare string.
struct Override {
  std::string path;
  std::string value;
};
/// Parses "path=value"; throws thintool::Error.
Override parseOverride(const std::string& text);

/// Reads a scene file, applying the overrides first. Throws thintool::Error.
SceneSpec loadScene(const std::string& path, const std::vector<Override>& overrides = {});
/// The same from text; relative file names resolve against baseFolder.
SceneSpec parseScene(const std::string& text, const std::string& sourceName, const std::string& baseFolder,
                     const std::vector<Override>& overrides = {});

/// A piece's convex solid in its own frame, for the ground truth and for building the Bullet shape.
ConvexSolid solidOf(const ToolPieceSpec& piece);

/// The tool's pose at time t (s) of its trajectory, and when the trajectory stops moving.
Pose poseAt(const TrajectorySpec& trajectory, double time);
double endTime(const TrajectorySpec& trajectory);

}  // namespace thintool::eval
