// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Random scenes from a seed, for testing ThinTool on cases nobody chose: a soft body (ellipsoid,
/// the vessel mesh, a pinned sheet or a box of tetrahedra) with random material and solver
/// settings, one random thin tool (plate, needle, wedge blade or a pair of jaws), kinematic on a
/// random waypoint path or dynamic and launched, at a random step. The scenes are judged only by
/// the evaluation suite's ground truth (SceneJudge.h), so that ThinTool cannot be tuned to them.
///
/// The same seed gives the same scene on every machine and standard library: the draws come from
/// std::mt19937_64's raw 64-bit outputs (whose sequence the standard fixes) through this file's own
/// mapping to numbers, never through std::uniform_*_distribution (whose algorithms it does not).
///
/// The ranges below are what the generator draws from; "log" marks a log-uniform draw, the others
/// are uniform. A scene's measured part is capped (kMaxSteps, kMaxSeconds, kWorkBudget) so that
/// a scene takes well under 0.2 s on average in a Release build.

#include "SceneFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace thintool::eval {

namespace generated {

// Soft body: which mesh, with these chances.
inline constexpr double kEllipsoidChance = 0.35;
inline constexpr double kObjChance = 0.15;   ///< eval/scenes/vessel.obj, closed
inline constexpr double kSheetChance = 0.25;
// The rest (0.25): the tetra box.

/// Ellipsoid: faces (log), the exact hull above kExactHullFaces; radius per axis; its centre puts
/// its lowest point on the ground.
inline constexpr int kMinEllipsoidFaces = 128;
inline constexpr int kMaxEllipsoidFaces = 16384;
inline constexpr int kExactHullFaces = 2000;
inline constexpr double kMinRadius = 0.2;  ///< m
inline constexpr double kMaxRadius = 1;    ///< m
/// The vessel (a capsule 2.4 m long, radius 0.35 m): scale, resting on the ground.
inline constexpr double kMinVesselScale = 0.4;
inline constexpr double kMaxVesselScale = 1;
/// Sheet: nodes a side, side, centre height; pinned at its four corners.
inline constexpr int kMinSheetNodes = 8;
inline constexpr int kMaxSheetNodes = 48;
inline constexpr double kMinSheetSize = 0.5;    ///< m
inline constexpr double kMaxSheetSize = 2;      ///< m
inline constexpr double kMinSheetHeight = 0.5;  ///< m
inline constexpr double kMaxSheetHeight = 1.5;  ///< m
/// Tetra box: cells a side, edge; resting on the ground.
inline constexpr int kMinTetraCells = 2;
inline constexpr int kMaxTetraCells = 6;
inline constexpr double kMinTetraEdge = 0.3;  ///< m
inline constexpr double kMaxTetraEdge = 1.2;  ///< m

// Material and solver.
inline constexpr double kMinLinearStiffness = 0.1;  ///< kLST
inline constexpr double kMaxLinearStiffness = 1;
inline constexpr double kMaxPressure = 100;         ///< kPR, from 0; 0 for sheets and tetra boxes
inline constexpr int kMinPositionIterations = 1;
inline constexpr int kMaxPositionIterations = 20;
inline constexpr double kMinMargin = 0.005;  ///< m, log
inline constexpr double kMaxMargin = 0.25;   ///< m
inline constexpr double kMinSoftMass = 0.1;  ///< kg, log
inline constexpr double kMaxSoftMass = 5;    ///< kg
inline constexpr double kMinFriction = 0.2;  ///< kDF
inline constexpr double kMaxFriction = 1;

// Tool: which kind, with these chances.
inline constexpr double kPlateChance = 0.3;
inline constexpr double kNeedleChance = 0.25;
inline constexpr double kBladeChance = 0.25;
// The rest (0.2): jaws.
/// Plate: a box, thin along its y axis; thickness (log), width and depth.
inline constexpr double kMinPlateThickness = 0.001;  ///< m
inline constexpr double kMaxPlateThickness = 0.02;   ///< m
inline constexpr double kMinPlateWidth = 0.1;        ///< m
inline constexpr double kMaxPlateWidth = 0.8;        ///< m
/// Needle: a square bar along its x axis.
inline constexpr double kMinNeedleWidth = 0.001;  ///< m
inline constexpr double kMaxNeedleWidth = 0.005;  ///< m
inline constexpr double kMinNeedleLength = 0.2;   ///< m
inline constexpr double kMaxNeedleLength = 1;     ///< m
/// Blade: a convex hull, a triangular prism along z whose cross-section tapers from a back
/// (thickness along x, height along y) to an edge at its lowest y.
inline constexpr double kMinBladeLength = 0.1;      ///< m
inline constexpr double kMaxBladeLength = 0.5;      ///< m
inline constexpr double kMinBladeHeight = 0.02;     ///< m
inline constexpr double kMaxBladeHeight = 0.1;      ///< m
inline constexpr double kMinBladeThickness = 0.002; ///< m, at the back
inline constexpr double kMaxBladeThickness = 0.01;  ///< m
/// Jaws: two plates (thickness as a plate's, width and depth below) either side of a gap along y.
inline constexpr double kMinJawWidth = 0.1;  ///< m
inline constexpr double kMaxJawWidth = 0.4;  ///< m
inline constexpr double kMinJawGap = 0.005;  ///< m
inline constexpr double kMaxJawGap = 0.06;   ///< m
/// Dynamic tools: this share of the scenes, with this mass (log); the rest are kinematic.
inline constexpr double kDynamicChance = 0.2;
inline constexpr double kMinToolMass = 0.05;  ///< kg
inline constexpr double kMaxToolMass = 2;     ///< kg

// Motion: waypoints. The tool starts along a random approach direction (the upper hemisphere for
// a closed body, any for a sheet, whose ground is then removed when the tool comes from below) at
// a clearance beyond the body's bounding box plus its margin, with a random tilt (half of the
// scenes: its leading edge or tip turned to the body, give or take 15°). Then 2 to 6 segments:
// the first approaches a point of the body's centre region (its bounding box's middle half; for a
// sheet, up to a quarter of its side either side of it), the last leaves to a point outside, and
// those between go to another centre point, back part of the way (a reversal) or nowhere (a hold,
// 2 to 20 steps). The path is planned against the body as built and moved by the runner onto the
// body as it settled (TrajectorySpec::plannedBodyBox), so the clearance holds however it settled.
inline constexpr double kMinClearance = 0.02;  ///< m, log; shrunk (not below the least) when the
                                               ///< speed could not cover it in a third of the run
inline constexpr double kMaxClearance = 0.3;   ///< m
inline constexpr int kMinSegments = 2;
inline constexpr int kMaxSegments = 6;
inline constexpr double kMinSpeed = 0.01;  ///< m/s, log, the whole path's
inline constexpr double kMaxSpeed = 50;    ///< m/s
/// Turning: none in kNoTurnChance of the scenes; else each moving segment turns, with even
/// chance, about its own random axis at a rate (log) per step.
inline constexpr double kNoTurnChance = 0.4;
inline constexpr double kMinTurnDegreesPerStep = 0.5;
inline constexpr double kMaxTurnDegreesPerStep = 180;

// Time. The cost of a scene is about its soft nodes times its steps (settling and measured), and
// the large bodies at fine steps would take most of the time of a run of seeds: kWorkBudget caps
// the node-steps. The step is log-uniform from the finer of kMinTimeStep and the finest step at
// which settling plus kMinMeasuredSteps fit the budget, to kMaxTimeStep; the measured steps are
// then cut to what is left of the budget, down to kMinMeasuredSteps. Only bodies of more than
// some 600 to 1,400 nodes (by the settle's length: ellipsoids from 1,200 to 2,800 faces, sheets
// from 24 to 37 nodes a side) are held to coarser steps.
inline constexpr double kMinTimeStep = 1.0 / 1000;  ///< s, log
inline constexpr double kMaxTimeStep = 1.0 / 30;    ///< s
inline constexpr double kMinSettleSeconds = 0.2;
inline constexpr double kMaxSettleSeconds = 0.5;
/// The measured steps: the path's end plus 5 to 15 held steps, at most this many steps and seconds.
inline constexpr int kMaxSteps = 150;
inline constexpr double kMaxSeconds = 1.5;
inline constexpr int kMinMeasuredSteps = 20;
inline constexpr double kWorkBudget = 3e5;  ///< soft nodes × steps

// Bullet's own kinds (GeneratorOptions::bulletKinds), from a stream of draws of their own.
/// Round tools, as Bullet's demos drape cloth over spheres, capsules and compounds: in this share
/// of the scenes the tool is, with even chances, a ball, a capsule along its x axis, or a compound
/// of a box and a ball side by side (the box a cube of the ball's diameter); each round piece a
/// hull of kRoundSegments meridians and kRoundRings steps from pole to pole.
inline constexpr double kRoundToolChance = 0.3;
inline constexpr int kRoundSegments = 12;
inline constexpr int kRoundRings = 8;
inline constexpr double kMinBallRadius = 0.01;     ///< m, log
inline constexpr double kMaxBallRadius = 0.3;      ///< m
inline constexpr double kMinCapsuleRadius = 0.002; ///< m, log
inline constexpr double kMaxCapsuleRadius = 0.03;  ///< m
inline constexpr double kMinCapsuleLength = 0.1;   ///< m, between its caps' centres
inline constexpr double kMaxCapsuleLength = 0.6;   ///< m
/// Pose matching (Bullet's kMT with setPose(false, true), its demos' torus) in this share of the
/// scenes, at a kMT drawn between these.
inline constexpr double kPoseMatchingChance = 0.3;
inline constexpr double kMinPoseMatching = 0.05;
inline constexpr double kMaxPoseMatching = 0.5;
/// Draped cloth, as Bullet's demos drop cloth over resting bodies: in this share of the sheet
/// scenes the sheet is free (no pinned corner) and starts above a kinematic tool that waits under
/// its middle half, on the ground, without settling. It falls from the soft margin plus a
/// clearance (kMinClearance..kMaxClearance, log) over the tool's top, or from as high as it falls
/// in a third of the measured time; the tool holds until it has landed and 2 to 20 steps more,
/// then makes 0 to 3 moves at the scene's speed and turn, each up by 0 to half the sheet's side
/// and sideways by up to a quarter of it: lifting the cloth, never pressing it to the ground, where
/// a thin tool's cloth has no way out. The tool's centre stays its reach plus the margin and
/// kDrapeGroundGap above the ground, whichever way it turns.
inline constexpr double kDrapeChance = 0.4;
inline constexpr double kDrapeGroundGap = 0.05;  ///< m
/// Cut cloth, as Bullet's demos cut it: in this share of the sheet scenes (pinned or draped) a slit
/// is cut through the sheet at a time between 20 and 80 % of the run (SoftBodySpec::Cut): through a
/// point of its middle half, at any horizontal angle, as long as these shares of its side (beyond
/// one, it may part the sheet in two). Never a pose-matched sheet: Bullet's btSoftBody::cutLink
/// appends nodes but not their pose's rest offsets and weights, which its pose matching then reads
/// past the end of.
inline constexpr double kCutChance = 0.3;
inline constexpr double kMinCutShare = 0.2;
inline constexpr double kMaxCutShare = 1.5;

}  // namespace generated

struct GeneratorOptions {
  /// Also draw Bullet's own kinds that the scenes above leave out: round tools, pose-matched
  /// bodies, draped cloth and cut cloth (the constants above). The rest of each seed's scene stays
  /// what it is without them: their draws come from a stream of their own.
  bool bulletKinds = false;
};

/// The scene of this seed, named "generated-<seed>", algorithm Swept (ThinTool's default).
/// sceneFolder: eval/scenes, where vessel.obj is read from. Throws thintool::Error when the
/// vessel cannot be read.
SceneSpec generateScene(std::uint64_t seed, const std::string& sceneFolder, const GeneratorOptions& options = {});

/// One line: the soft body, its material, the tool, its motion (the start as planned, before the
/// runner moves the path onto the settled body) and the step.
std::string describeScene(const SceneSpec& scene);

/// Seeds from a file such as eval/generated/regressions.txt: one a line, '#' starts a comment,
/// blank lines skipped. Throws thintool::Error naming the file and line of anything else.
std::vector<std::uint64_t> readSeedFile(const std::string& path);
/// A seed written as a whole number. Throws thintool::Error.
std::uint64_t parseSeed(const std::string& text);

}  // namespace thintool::eval
