// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SceneGenerator.h"

#include "ObjMesh.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace thintool::eval {

namespace {

using namespace generated;

constexpr double kDegrees = kPi / 180;

// Numbers from the engine's raw outputs, by arithmetic this file fixes.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : m_engine(seed) {}

  /// [0, 1), from the output's top 53 bits.
  double unit() { return double(m_engine() >> 11) * 0x1.0p-53; }
  double uniform(double low, double high) { return low + (high - low) * unit(); }
  /// Even in the logarithm; clamped, since exp(log(high)) may round a hair past high.
  double logUniform(double low, double high) {
    return std::clamp(std::exp(std::log(low) + (std::log(high) - std::log(low)) * unit()), low, high);
  }
  /// low..high inclusive (the modulo's bias is below 2⁻⁵⁰ for these small ranges).
  int integer(int low, int high) { return low + int(m_engine() % std::uint64_t(high - low + 1)); }
  bool chance(double probability) { return unit() < probability; }
  /// A unit vector, even over the sphere: a point of the unit ball by rejection, scaled out.
  Vec3 direction() {
    for (;;) {
      const Vec3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      const double l = lengthSquared(v);
      if (l > 1e-6 && l <= 1) return v / std::sqrt(l);
    }
  }

 private:
  std::mt19937_64 m_engine;
};

// SplitMix64's finaliser (Steele, Lea and Flood, "Fast splittable pseudorandom number generators",
// 2014): a second stream's seed that shares nothing with the first's. The engine's own seeding
// keeps nearby seeds' early outputs alike (seeds 10 and 24 drew the same second number).
std::uint64_t splitMix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The rotation vector (degrees) of a rotation matrix, through its quaternion (Shepperd's method,
// steady at any angle).
Vec3 rotationVectorOf(const Mat3& m) {
  const double m00 = m.row[0].x, m11 = m.row[1].y, m22 = m.row[2].z;
  const double trace = m00 + m11 + m22;
  double w, x, y, z;
  if (trace >= m00 && trace >= m11 && trace >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 + trace));
    w = s / 4, x = (m.row[2].y - m.row[1].z) / s, y = (m.row[0].z - m.row[2].x) / s, z = (m.row[1].x - m.row[0].y) / s;
  } else if (m00 >= m11 && m00 >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 + m00 - m11 - m22));
    w = (m.row[2].y - m.row[1].z) / s, x = s / 4, y = (m.row[0].y + m.row[1].x) / s, z = (m.row[0].z + m.row[2].x) / s;
  } else if (m11 >= m22) {
    const double s = 2 * std::sqrt(std::max(0.0, 1 - m00 + m11 - m22));
    w = (m.row[0].z - m.row[2].x) / s, x = (m.row[0].y + m.row[1].x) / s, y = s / 4, z = (m.row[1].z + m.row[2].y) / s;
  } else {
    const double s = 2 * std::sqrt(std::max(0.0, 1 - m00 - m11 + m22));
    w = (m.row[1].x - m.row[0].y) / s, x = (m.row[0].z + m.row[2].x) / s, y = (m.row[1].z + m.row[2].y) / s, z = s / 4;
  }
  const Vec3 axis{x, y, z};
  const double sine = length(axis);
  if (sine < 1e-12) return {};
  const double angle = 2 * std::atan2(sine, w);
  return axis * (angle / sine / kDegrees);
}

// The shortest rotation taking unit vector from onto unit vector to.
Mat3 rotationBetween(const Vec3& from, const Vec3& to) {
  const Vec3 axis = cross(from, to);
  const double sine = length(axis);
  const double cosine = dot(from, to);
  if (sine > 1e-9) return rotationAboutAxis(axis / sine, std::atan2(sine, cosine));
  if (cosine > 0) return {};
  // Opposite: half a turn about any axis across them.
  const Vec3 across = std::abs(from.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return rotationAboutAxis(normalizedOrZero(cross(from, across)), kPi);
}

enum class ToolKind { Plate, Needle, Blade, Jaws };

ToolPieceSpec boxPiece(const Vec3& halfExtents) {
  ToolPieceSpec piece;
  piece.kind = ToolPieceSpec::Kind::Box;
  piece.halfExtents = halfExtents;
  return piece;
}

// A triangular prism along z: the back (thickness along x) at +height/2, the edge at -height/2.
ToolPieceSpec bladePiece(double length, double height, double thickness) {
  ToolPieceSpec piece;
  piece.kind = ToolPieceSpec::Kind::Hull;
  ConvexSolid& hull = piece.hull;
  for (double z : {-length / 2, length / 2}) {
    hull.vertices.push_back({-thickness / 2, height / 2, z});
    hull.vertices.push_back({thickness / 2, height / 2, z});
    hull.vertices.push_back({0, -height / 2, z});
  }
  // Two end caps and the three sides, each side two triangles (SolidDistance orients them).
  hull.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  return piece;
}

// A round hull about the x axis: `profile` lists (x, distance from the axis) from one pole to the
// other, each ring kRoundSegments points round the axis (a pole, at distance 0, one point).
ToolPieceSpec roundPiece(const std::vector<std::array<double, 2>>& profile) {
  ToolPieceSpec piece;
  piece.kind = ToolPieceSpec::Kind::Hull;
  ConvexSolid& hull = piece.hull;
  std::vector<int> first;  // each ring's first vertex
  for (const auto& [x, r] : profile) {
    first.push_back(int(hull.vertices.size()));
    const int count = r > 0 ? kRoundSegments : 1;
    for (int k = 0; k < count; ++k) {
      const double angle = 2 * kPi * k / kRoundSegments;
      hull.vertices.push_back({x, r * std::cos(angle), r * std::sin(angle)});
    }
  }
  // Between each pair of rings: a fan at a pole, two triangles a quad elsewhere (SolidDistance
  // orients them).
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const bool poleHere = !(profile[i][1] > 0);
    const bool poleNext = !(profile[i + 1][1] > 0);
    for (int k = 0; k < kRoundSegments; ++k) {
      const int k1 = (k + 1) % kRoundSegments;
      const int a = first[i] + (poleHere ? 0 : k), b = first[i] + (poleHere ? 0 : k1);
      const int c = first[i + 1] + (poleNext ? 0 : k), d = first[i + 1] + (poleNext ? 0 : k1);
      if (!poleHere) hull.triangles.push_back({a, b, c});
      if (!poleNext) hull.triangles.push_back({b, d, c});
    }
  }
  return piece;
}

// Rings from pole to pole of a sphere of this radius, its halves apart by `length` along x.
std::vector<std::array<double, 2>> capsuleProfile(double radius, double length) {
  std::vector<std::array<double, 2>> profile;
  for (int i = 0; i <= kRoundRings; ++i) {
    const double latitude = kPi * i / kRoundRings;
    const double x = radius * std::cos(latitude) + (2 * i < kRoundRings ? length / 2 : -length / 2);
    profile.push_back({x, i == 0 || i == kRoundRings ? 0 : radius * std::sin(latitude)});
    if (2 * i == kRoundRings && length > 0) profile.push_back({-length / 2, radius});
  }
  profile[kRoundRings / 2][0] = length / 2;
  return profile;
}

// A round tool (kRoundToolChance): a ball, a capsule, or a box and a ball side by side.
std::vector<ToolPieceSpec> drawRoundTool(Draw& draw, std::string& name) {
  const double what = draw.unit();
  if (what < 1.0 / 3) {
    name = "ball";
    return {roundPiece(capsuleProfile(draw.logUniform(kMinBallRadius, kMaxBallRadius), 0))};
  }
  if (what < 2.0 / 3) {
    name = "capsule";
    const double radius = draw.logUniform(kMinCapsuleRadius, kMaxCapsuleRadius);
    return {roundPiece(capsuleProfile(radius, draw.uniform(kMinCapsuleLength, kMaxCapsuleLength)))};
  }
  name = "box and ball";
  const double radius = draw.logUniform(kMinBallRadius, kMaxBallRadius);
  std::vector<ToolPieceSpec> pieces{boxPiece({radius, radius, radius}), roundPiece(capsuleProfile(radius, 0))};
  pieces[0].offset.translation = {-radius, 0, 0};
  pieces[1].offset.translation = {radius * 1.2, 0, 0};
  return pieces;
}

std::vector<ToolPieceSpec> drawTool(Draw& draw, ToolKind kind) {
  switch (kind) {
    case ToolKind::Plate: {
      const double thickness = draw.logUniform(kMinPlateThickness, kMaxPlateThickness);
      const double width = draw.uniform(kMinPlateWidth, kMaxPlateWidth);
      const double depth = draw.uniform(kMinPlateWidth, kMaxPlateWidth);
      return {boxPiece({width / 2, thickness / 2, depth / 2})};
    }
    case ToolKind::Needle: {
      const double width = draw.uniform(kMinNeedleWidth, kMaxNeedleWidth);
      const double length = draw.uniform(kMinNeedleLength, kMaxNeedleLength);
      return {boxPiece({length / 2, width / 2, width / 2})};
    }
    case ToolKind::Blade: {
      const double length = draw.uniform(kMinBladeLength, kMaxBladeLength);
      const double height = draw.uniform(kMinBladeHeight, kMaxBladeHeight);
      const double thickness = draw.uniform(kMinBladeThickness, kMaxBladeThickness);
      return {bladePiece(length, height, thickness)};
    }
    case ToolKind::Jaws: break;
  }
  const double thickness = draw.logUniform(kMinPlateThickness, kMaxPlateThickness);
  const double width = draw.uniform(kMinJawWidth, kMaxJawWidth);
  const double depth = draw.uniform(kMinJawWidth, kMaxJawWidth);
  const double gap = draw.uniform(kMinJawGap, kMaxJawGap);
  std::vector<ToolPieceSpec> jaws(2, boxPiece({width / 2, thickness / 2, depth / 2}));
  jaws[0].offset.translation = {0, (gap + thickness) / 2, 0};
  jaws[1].offset.translation = {0, -(gap + thickness) / 2, 0};
  return jaws;
}

// Where a body's bounding box is and how far a tool must keep from it.
struct Bounds {
  Vec3 centre;
  Vec3 half;
};

// The distance along direction from the body's centre at which the tool's box (half extents
// toolHalf about its origin) clears the body's box grown by gap: the nearest of the three slabs.
double clearingDistance(const Bounds& body, const Vec3& toolHalf, double gap, const Vec3& direction) {
  double distance = 1e300;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(direction[axis]) < 1e-9) continue;
    distance = std::min(distance, (body.half[axis] + gap + toolHalf[axis]) / std::abs(direction[axis]));
  }
  return distance;
}

Vec3 upperHemisphere(Draw& draw) {
  Vec3 d = draw.direction();
  d.y = std::abs(d.y);
  return d;
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string significant(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

// A free cloth dropped on the tool, which waits under it and then lifts it (kDrapeChance): the
// scene's sheet, tool, tilt, speed and turn, a path of its own.
void drapeOverTool(SceneSpec& scene, ToolSpec& tool, double toolTop, double reach, double speed, double turnPerStep,
                   int stepCap, Draw& draw) {
  SoftBodySpec& soft = scene.soft;
  soft.pinnedCorners = false;
  scene.ground = true;
  scene.settleSeconds = 0;  // it would fall before the tool is there
  tool.mass = 0;
  const double dt = scene.timeStep;
  const double gravity = length(scene.gravity);
  const double fallTime = stepCap * dt / 3;
  const double drop =
      std::min(*soft.margin + draw.logUniform(kMinClearance, kMaxClearance), 0.5 * gravity * fallTime * fallTime);
  const double lowestCentre = reach + *soft.margin + kDrapeGroundGap;  // the tool's, whichever way it turns
  soft.centre.y = std::max(soft.centre.y, lowestCentre + toolTop + drop);
  const double side = soft.sheetSize;
  const Vec3 rest{draw.uniform(-0.25, 0.25) * side, soft.centre.y - drop - toolTop, draw.uniform(-0.25, 0.25) * side};

  TrajectorySpec& path = tool.trajectory;
  const Vec3 rotation = path.waypoints.front().rotation;
  path.plannedBodyBox.reset();
  path.waypoints.clear();
  path.waypoints.push_back({0, rest, rotation});
  long step = long(std::ceil(std::sqrt(2 * drop / gravity) / dt)) + draw.integer(2, 20);
  path.waypoints.push_back({double(step) * dt, rest, rotation});
  const int moves = draw.integer(0, 3);
  for (int i = 0; i < moves; ++i) {
    const TrajectorySpec::Waypoint last = path.waypoints.back();
    const Vec3 target = last.position + Vec3{draw.uniform(-0.25, 0.25) * side, draw.uniform(0, 0.5) * side,
                                             draw.uniform(-0.25, 0.25) * side};
    const long steps = std::max(1L, long(std::ceil(length(target - last.position) / (speed * dt))));
    Vec3 turned = last.rotation;
    if (turnPerStep > 0 && draw.chance(0.5)) turned += draw.direction() * (turnPerStep * double(steps));
    step += steps;
    path.waypoints.push_back({double(step) * dt, target, turned});
  }
  scene.duration = double(std::min<long>(stepCap, step + draw.integer(5, 15))) * dt;
}

}  // namespace

SceneSpec generateScene(std::uint64_t seed, const std::string& sceneFolder, const GeneratorOptions& options) {
  Draw draw(seed);
  Draw kinds(splitMix(seed));  // GeneratorOptions::bulletKinds' own stream
  SceneSpec scene;
  scene.name = "generated-" + std::to_string(seed);
  scene.algorithm = AlgorithmKind::Swept;
  scene.substeps = 1;
  scene.settleSeconds = draw.uniform(kMinSettleSeconds, kMaxSettleSeconds);

  // The soft body, and the box it starts in (grown where settling may spread or sag it).
  SoftBodySpec& soft = scene.soft;
  Bounds body;
  const double meshDraw = draw.unit();
  if (meshDraw < kEllipsoidChance) {
    soft.mesh = SoftBodySpec::Mesh::Ellipsoid;
    const double faces = draw.logUniform(kMinEllipsoidFaces, kMaxEllipsoidFaces);
    // CreateEllipsoid's res + 3 points make a closed hull of 2·(res + 1) faces.
    soft.resolution = std::max(kMinEllipsoidFaces / 2 - 1, int(std::lround(faces / 2)) - 1);
    soft.exactHull = 2 * (soft.resolution + 1) > kExactHullFaces;
    soft.radius = {draw.uniform(kMinRadius, kMaxRadius), draw.uniform(kMinRadius, kMaxRadius),
                   draw.uniform(kMinRadius, kMaxRadius)};
    soft.centre = {0, soft.radius.y, 0};
    body = {soft.centre, soft.radius};
  } else if (meshDraw < kEllipsoidChance + kObjChance) {
    soft.mesh = SoftBodySpec::Mesh::Obj;
    soft.objFile = "vessel.obj";
    soft.objMesh = loadObj(sceneFolder + "/" + soft.objFile);
    soft.scale = draw.uniform(kMinVesselScale, kMaxVesselScale);
    Vec3 low = soft.objMesh.vertices.front();
    Vec3 high = low;
    for (const Vec3& v : soft.objMesh.vertices) {
      low = componentMin(low, v);
      high = componentMax(high, v);
    }
    soft.centre = {0, -low.y * soft.scale, 0};
    body = {soft.centre + (low + high) * (0.5 * soft.scale), (high - low) * (0.5 * soft.scale)};
  } else if (meshDraw < kEllipsoidChance + kObjChance + kSheetChance) {
    soft.mesh = SoftBodySpec::Mesh::Sheet;
    soft.nodesPerSide = draw.integer(kMinSheetNodes, kMaxSheetNodes);
    soft.sheetSize = draw.uniform(kMinSheetSize, kMaxSheetSize);
    soft.centre = {0, draw.uniform(kMinSheetHeight, kMaxSheetHeight), 0};
    body = {soft.centre, {soft.sheetSize / 2, 0, soft.sheetSize / 2}};
  } else {
    soft.mesh = SoftBodySpec::Mesh::Tetra;
    soft.tetraCells = draw.integer(kMinTetraCells, kMaxTetraCells);
    soft.sheetSize = draw.uniform(kMinTetraEdge, kMaxTetraEdge);
    soft.centre = {0, soft.sheetSize / 2, 0};
    body = {soft.centre, Vec3{1, 1, 1} * (soft.sheetSize / 2)};
  }
  const bool sheet = soft.mesh == SoftBodySpec::Mesh::Sheet;

  // The step: log-uniform, but not so fine that settling and kMinMeasuredSteps would pass the
  // work budget on this many nodes.
  const double nodes = soft.mesh == SoftBodySpec::Mesh::Ellipsoid ? soft.resolution + 3
                       : soft.mesh == SoftBodySpec::Mesh::Obj     ? double(soft.objMesh.vertices.size())
                       : sheet                                    ? double(soft.nodesPerSide * soft.nodesPerSide)
                                                                  : std::pow(soft.tetraCells + 1, 3);
  const double affordableSteps = kWorkBudget / nodes;
  const double finestStep =
      affordableSteps > kMinMeasuredSteps ? scene.settleSeconds / (affordableSteps - kMinMeasuredSteps) : kMaxTimeStep;
  scene.timeStep = draw.logUniform(std::clamp(finestStep, kMinTimeStep, kMaxTimeStep), kMaxTimeStep);

  soft.linearStiffness = draw.uniform(kMinLinearStiffness, kMaxLinearStiffness);
  // Pressure holds up a closed surface; a sheet has no volume, and the tetra box's tetrahedra hold
  // it up (pressure on its few, light nodes flings it off the ground before the tool arrives).
  const double pressure = draw.uniform(0, kMaxPressure);
  soft.pressure = sheet || soft.mesh == SoftBodySpec::Mesh::Tetra ? 0 : pressure;
  soft.positionIterations = draw.integer(kMinPositionIterations, kMaxPositionIterations);
  soft.margin = draw.logUniform(kMinMargin, kMaxMargin);
  soft.mass = draw.logUniform(kMinSoftMass, kMaxSoftMass);
  soft.friction = draw.uniform(kMinFriction, kMaxFriction);
  if (options.bulletKinds && kinds.chance(kPoseMatchingChance)) {
    soft.poseMatching = kinds.uniform(kMinPoseMatching, kMaxPoseMatching);
  }

  // The tool.
  ToolSpec tool;
  const double toolDraw = draw.unit();
  const ToolKind kind = toolDraw < kPlateChance                                  ? ToolKind::Plate
                        : toolDraw < kPlateChance + kNeedleChance                ? ToolKind::Needle
                        : toolDraw < kPlateChance + kNeedleChance + kBladeChance ? ToolKind::Blade
                                                                                 : ToolKind::Jaws;
  static const char* const kToolNames[] = {"plate", "needle", "blade", "jaws"};
  tool.name = kToolNames[int(kind)];
  tool.pieces = drawTool(draw, kind);
  // The drawn tool's draws are taken all the same, so that the rest of the scene stays the seed's.
  const bool round = options.bulletKinds && kinds.chance(kRoundToolChance);
  if (round) tool.pieces = drawRoundTool(kinds, tool.name);
  if (draw.chance(kDynamicChance)) tool.mass = draw.logUniform(kMinToolMass, kMaxToolMass);

  // The approach: direction, tilt, start.
  Vec3 approach = sheet ? draw.direction() : upperHemisphere(draw);
  if (sheet && approach.y < 0) scene.ground = false;  // from below: the ground would be in the way
  Mat3 tilt;
  if (draw.chance(0.5)) {
    // The leading feature to the body: the needle's tip, the plate's and jaws' edge, the blade's
    // edge; rolled at random about the approach, then off by up to 15°.
    const Vec3 lead = kind == ToolKind::Blade && !round ? Vec3{0, -1, 0} : Vec3{1, 0, 0};
    const double roll = draw.uniform(0, 2 * kPi);
    const Vec3 jitterAxis = draw.direction();
    const double jitter = draw.uniform(0, 15) * kDegrees;
    tilt = rotationAboutAxis(jitterAxis, jitter) * rotationAboutAxis(-approach, roll) * rotationBetween(lead, -approach);
  } else {
    const Vec3 axis = draw.direction();
    tilt = rotationAboutAxis(axis, draw.uniform(0, 180) * kDegrees);
  }
  Vec3 toolHalf;
  double reach = 0;
  double toolTop = -std::numeric_limits<double>::max();  // above the tool's origin
  for (const ToolPieceSpec& piece : tool.pieces) {
    for (const Vec3& v : solidOf(piece).vertices) {
      const Vec3 p = tilt * piece.offset.apply(v);
      toolHalf = componentMax(toolHalf, {std::abs(p.x), std::abs(p.y), std::abs(p.z)});
      reach = std::max(reach, length(p));
      toolTop = std::max(toolTop, p.y);
    }
  }

  const double speed = draw.logUniform(kMinSpeed, kMaxSpeed);
  const double dt = scene.timeStep;
  const long settleSteps = std::lround(scene.settleSeconds / dt);
  const int stepCap = int(std::max<double>(
      kMinMeasuredSteps, std::min({double(kMaxSteps), std::floor(kMaxSeconds / dt + 1e-9),
                                   std::floor(affordableSteps) - double(settleSteps)})));
  double clearance = draw.logUniform(kMinClearance, kMaxClearance);
  // A slow tool at a long clearance would spend the whole run in the air.
  clearance = std::min(clearance, std::max(kMinClearance, speed * stepCap * dt / 3));
  const double gap = *soft.margin + clearance;
  Vec3 start = body.centre + approach * clearingDistance(body, toolHalf, gap, approach);
  if (scene.ground) start.y = std::max(start.y, toolHalf.y + clearance);  // not in the ground either

  const bool turning = !draw.chance(kNoTurnChance);
  const double turnPerStep = turning ? draw.logUniform(kMinTurnDegreesPerStep, kMaxTurnDegreesPerStep) : 0;

  TrajectorySpec& path = tool.trajectory;
  path.kind = TrajectorySpec::Kind::Waypoints;
  // Planned against the body as built; the runner moves the path onto the body as it settles.
  path.plannedBodyBox = std::array<Vec3, 2>{body.centre - body.half, body.centre + body.half};
  path.waypoints.push_back({0, start, rotationVectorOf(tilt)});
  long step = 0;
  // The middle half of the body's box; for a sheet, as far either side of it as its quarter side,
  // to push it or through it.
  const double middleHeight = sheet ? soft.sheetSize / 4 : body.half.y / 2;
  auto centrePoint = [&] {
    return body.centre + Vec3{draw.uniform(-0.5, 0.5) * body.half.x, draw.uniform(-1, 1) * middleHeight,
                              draw.uniform(-0.5, 0.5) * body.half.z};
  };
  auto moveTo = [&](const Vec3& target) {
    const TrajectorySpec::Waypoint& last = path.waypoints.back();
    const long steps = std::max(1L, long(std::ceil(length(target - last.position) / (speed * dt))));
    Vec3 rotation = last.rotation;
    if (turning && draw.chance(0.5)) rotation += draw.direction() * (turnPerStep * double(steps));
    step += steps;
    path.waypoints.push_back({double(step) * dt, target, rotation});
  };
  const int segments = draw.integer(kMinSegments, kMaxSegments);
  moveTo(centrePoint());
  for (int s = 1; s + 1 < segments; ++s) {
    const double what = draw.unit();
    const std::size_t n = path.waypoints.size();
    if (what < 0.45) {
      moveTo(centrePoint());
    } else if (what < 0.75) {
      const Vec3& here = path.waypoints[n - 1].position;
      moveTo(here + (path.waypoints[n - 2].position - here) * draw.uniform(0.3, 1));
    } else {
      const TrajectorySpec::Waypoint last = path.waypoints.back();
      step += draw.integer(2, 20);
      path.waypoints.push_back({double(step) * dt, last.position, last.rotation});
    }
  }
  if (draw.chance(0.5)) {
    moveTo(start);
  } else {
    const Vec3 away = sheet && !scene.ground ? draw.direction() : upperHemisphere(draw);
    const Vec3 reachHalf = Vec3{1, 1, 1} * reach;  // the tool may have turned: its sphere
    Vec3 exit = body.centre + away * clearingDistance(body, reachHalf, gap, away);
    if (scene.ground) exit.y = std::max(exit.y, reach + clearance);
    moveTo(exit);
  }

  const long measured = std::min<long>(stepCap, step + draw.integer(5, 15));
  scene.duration = double(measured) * dt;
  scene.holdSeconds = 0;
  if (options.bulletKinds && sheet && kinds.chance(kDrapeChance)) {
    drapeOverTool(scene, tool, toolTop, reach, speed, turnPerStep, stepCap, kinds);
  }
  // Not a pose-matched sheet: Bullet's cut appends nodes without their rest offsets and weights,
  // and its pose matching then reads past the end of those arrays (btSoftBody::updatePose).
  if (options.bulletKinds && sheet && kinds.chance(kCutChance) && soft.poseMatching == 0) {
    SoftBodySpec::Cut cut;
    cut.time = kinds.uniform(0.2, 0.8) * scene.duration;
    cut.point = soft.centre + Vec3{kinds.uniform(-0.25, 0.25) * soft.sheetSize, 0,
                                   kinds.uniform(-0.25, 0.25) * soft.sheetSize};
    const double angle = kinds.uniform(0, kPi);
    cut.direction = {std::cos(angle), 0, std::sin(angle)};
    cut.halfLength = kinds.uniform(kMinCutShare, kMaxCutShare) * soft.sheetSize / 2;
    soft.cut = cut;
  }
  scene.tools.push_back(std::move(tool));
  return scene;
}

std::string describeScene(const SceneSpec& scene) {
  const SoftBodySpec& soft = scene.soft;
  std::string text = scene.name + ": ";
  switch (soft.mesh) {
    case SoftBodySpec::Mesh::Ellipsoid:
      text += "ellipsoid " + std::to_string(2 * (soft.resolution + 1)) + " faces" +
              (soft.exactHull ? " (exact hull)" : "") + " radii " + fixed(soft.radius.x, 2) + " " +
              fixed(soft.radius.y, 2) + " " + fixed(soft.radius.z, 2) + " m";
      break;
    case SoftBodySpec::Mesh::Obj:
      text += "mesh " + soft.objFile + " x" + fixed(soft.scale, 2) + " (" +
              std::to_string(soft.objMesh.triangles.size()) + " faces)";
      break;
    case SoftBodySpec::Mesh::Sheet:
      text += "sheet " + std::to_string(soft.nodesPerSide) + "x" + std::to_string(soft.nodesPerSide) + " nodes " +
              fixed(soft.sheetSize, 2) + " m at y " + fixed(soft.centre.y, 2) + " m" + (soft.pinnedCorners ? "" : " free") +
              (scene.ground ? "" : " no ground");
      if (soft.cut) {
        text += ", cut " + fixed(2 * soft.cut->halfLength, 2) + " m long at " + fixed(soft.cut->time, 3) + " s";
      }
      break;
    case SoftBodySpec::Mesh::Tetra:
      text += "tetra box " + std::to_string(soft.tetraCells) + "^3 cells " + fixed(soft.sheetSize, 2) + " m";
      break;
  }
  text += "; kLST " + fixed(soft.linearStiffness, 2) + " kPR " + fixed(soft.pressure, 1) + " piter " +
          (soft.positionIterations ? std::to_string(*soft.positionIterations) : std::string("-")) + " margin " +
          (soft.margin ? significant(*soft.margin) : std::string("-")) + " m mass " + significant(soft.mass) +
          " kg kDF " + fixed(soft.friction, 2);
  if (soft.poseMatching > 0) text += " kMT " + fixed(soft.poseMatching, 2);

  for (const ToolSpec& tool : scene.tools) {
    text += "; " + tool.name;
    const ToolPieceSpec& piece = tool.pieces.front();
    const ConvexSolid solid = solidOf(piece);
    Vec3 low = solid.vertices.front();
    Vec3 high = low;
    for (const Vec3& v : solid.vertices) {
      low = componentMin(low, v);
      high = componentMax(high, v);
    }
    const Vec3 size = high - low;
    text += " " + significant(size.x * 1000) + "x" + significant(size.y * 1000) + "x" + significant(size.z * 1000) + " mm";
    if (tool.name == "jaws") {
      const double gap = length(tool.pieces[0].offset.translation - tool.pieces[1].offset.translation) - size.y;
      text += " gap " + significant(gap * 1000) + " mm";
    }
    text += tool.mass > 0 ? ", dynamic " + significant(tool.mass) + " kg" : ", kinematic";

    const std::vector<TrajectorySpec::Waypoint>& points = tool.trajectory.waypoints;
    double peakSpeed = 0;
    double peakTurn = 0;  // degrees a step, of the rotation vector
    for (std::size_t i = 1; i < points.size(); ++i) {
      const double duration = points[i].time - points[i - 1].time;
      peakSpeed = std::max(peakSpeed, length(points[i].position - points[i - 1].position) / duration);
      peakTurn = std::max(peakTurn, length(points[i].rotation - points[i - 1].rotation) / duration * scene.timeStep);
    }
    text += "; " + std::to_string(points.size() > 0 ? points.size() - 1 : 0) + " segments, " + significant(peakSpeed) +
            " m/s, turn " + significant(peakTurn) + " deg/step";
    if (!points.empty()) {
      const Vec3& p = points.front().position;
      text += ", from " + fixed(p.x, 2) + " " + fixed(p.y, 2) + " " + fixed(p.z, 2);
    }
  }
  text += "; dt 1/" + significant(1 / scene.timeStep) + " s, settle " + fixed(scene.settleSeconds, 2) + " s, " +
          std::to_string(long(std::lround(scene.duration / scene.timeStep))) + " steps";
  return text;
}

std::uint64_t parseSeed(const std::string& text) {
  std::size_t used = 0;
  unsigned long long value = 0;
  try {
    value = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || text[0] == '-') {
    throw Error("'" + text + "' is not a seed (a whole number)");
  }
  return value;
}

std::vector<std::uint64_t> readSeedFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot read the file");
  std::vector<std::uint64_t> seeds;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string word;
    if (!(words >> word)) continue;
    try {
      seeds.push_back(parseSeed(word));
    } catch (const Error& e) {
      throw Error(path + ":" + std::to_string(number) + ": " + e.what());
    }
    if (words >> word) throw Error(path + ":" + std::to_string(number) + ": one seed a line, then '#' and a comment");
  }
  return seeds;
}

}  // namespace thintool::eval
