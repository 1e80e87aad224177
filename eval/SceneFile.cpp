// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "SceneFile.h"

#include "Json.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace thintool::eval {

namespace {

constexpr double kDegrees = kPi / 180;

Vec3 toVec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

Vec3 vec3Or(const JsonField& object, std::string_view key, const Vec3& fallback) {
  const std::optional<JsonField> field = object.find(key);
  return field ? toVec3(field->vec3()) : fallback;
}

std::string folderOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string resolve(const std::string& baseFolder, const std::string& file) {
  return !file.empty() && file[0] == '/' ? file : baseFolder + "/" + file;
}

// A step may be written as a fraction, "1/240", as the results' tables write it.
double timeStepOf(const JsonField& field) {
  if (field.value().kind == JsonValue::Kind::String) {
    const std::string text = field.string();
    double numerator = 0;
    double denominator = 0;
    char slash = 0;
    std::istringstream in(text);
    if (in >> numerator >> slash >> denominator && slash == '/' && in.peek() == EOF && denominator > 0 &&
        numerator > 0) {
      return numerator / denominator;
    }
    field.fail("expected a step in seconds, as a number or a fraction such as \"1/240\", found \"" + text + "\"");
  }
  const double value = field.number();
  if (!(value > 0)) field.fail("expected a step greater than 0 s");
  return value;
}

Pose offsetOf(const JsonField& shape) {
  const std::optional<JsonField> offset = shape.find("offset");
  if (!offset) return {};
  offset->allowOnly({"position", "rotation"});
  return poseOf(vec3Or(*offset, "position", {}), vec3Or(*offset, "rotation", {}));
}

void readPieces(const JsonField& shape, const std::string& baseFolder, std::vector<ToolPieceSpec>& pieces,
                bool inCompound) {
  const std::string type = shape.at("type").oneOf({"box", "hull", "compound"});
  ToolPieceSpec piece;
  piece.offset = offsetOf(shape);
  if (type == "box") {
    shape.allowOnly({"type", "half_extents", "offset"});
    piece.kind = ToolPieceSpec::Kind::Box;
    const JsonField extents = shape.at("half_extents");
    piece.halfExtents = toVec3(extents.vec3());
    if (!(piece.halfExtents.x > 0 && piece.halfExtents.y > 0 && piece.halfExtents.z > 0)) {
      extents.fail("expected three half extents greater than 0 m");
    }
  } else if (type == "hull") {
    shape.allowOnly({"type", "file", "scale", "offset"});
    piece.kind = ToolPieceSpec::Kind::Hull;
    const JsonField file = shape.at("file");
    piece.objFile = file.string();
    piece.scale = shape.positive("scale", 1);
    TriangleMesh mesh;
    try {
      mesh = loadObj(resolve(baseFolder, piece.objFile));
      for (Vec3& v : mesh.vertices) v *= piece.scale;
      SolidDistance check({mesh.vertices, mesh.triangles});
    } catch (const Error& error) {
      file.fail(std::string("the hull's OBJ is unusable: ") + error.what());
    }
    piece.hull = {mesh.vertices, mesh.triangles};
  } else {
    if (inCompound) shape.fail("a compound's part cannot be a compound");
    shape.allowOnly({"type", "parts"});
    const JsonField parts = shape.at("parts");
    if (parts.size() == 0) parts.fail("expected at least one part");
    for (std::size_t i = 0; i < parts.size(); ++i) readPieces(parts.at(i), baseFolder, pieces, true);
    return;
  }
  pieces.push_back(piece);
}

std::vector<TrajectorySpec::Waypoint> readCsvTrajectory(const JsonField& field, const std::string& path) {
  std::ifstream file(path);
  if (!file) field.fail("cannot read the trajectory file '" + path + "'");
  std::vector<TrajectorySpec::Waypoint> waypoints;
  std::string line;
  int lineNumber = 0;
  while (std::getline(file, line)) {
    ++lineNumber;
    if (line.empty() || line[0] == '#' || (lineNumber == 1 && line[0] == 't')) continue;  // comment, header
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream in(line);
    std::vector<double> values;
    double value = 0;
    while (in >> value) values.push_back(value);
    const std::string where = path + ":" + std::to_string(lineNumber) + ": ";
    if (!in.eof() || (values.size() != 4 && values.size() != 7)) {
      throw Error(where + "expected t,x,y,z or t,x,y,z,rx,ry,rz (s, m, degrees)");
    }
    for (double v : values) {
      if (!std::isfinite(v)) throw Error(where + "a value is not a finite number");
    }
    TrajectorySpec::Waypoint w;
    w.time = values[0];
    w.position = {values[1], values[2], values[3]};
    if (values.size() == 7) w.rotation = {values[4], values[5], values[6]};
    if (!waypoints.empty() && !(w.time > waypoints.back().time)) {
      throw Error(where + "times must increase from row to row");
    }
    waypoints.push_back(w);
  }
  if (waypoints.empty()) field.fail("the trajectory file '" + path + "' has no row");
  return waypoints;
}

TrajectorySpec readTrajectory(const JsonField& field, const std::string& baseFolder) {
  TrajectorySpec trajectory;
  const std::string type = field.at("type").oneOf({"constant_velocity", "waypoints", "csv"});
  if (type == "constant_velocity") {
    field.allowOnly({"type", "start", "start_clearance", "rotation", "direction", "speed", "distance"});
    trajectory.kind = TrajectorySpec::Kind::ConstantVelocity;
    trajectory.start = toVec3(field.at("start").vec3());
    trajectory.rotation = vec3Or(field, "rotation", {});
    const Vec3 direction = vec3Or(field, "direction", trajectory.direction);
    trajectory.direction = normalizedOrZero(direction);
    if (lengthSquared(trajectory.direction) == 0) field.at("direction").fail("expected a direction, not [0, 0, 0]");
    trajectory.speed = field.positive("speed", trajectory.speed);
    if (field.has("start_clearance")) trajectory.startClearance = field.at("start_clearance").number();
    trajectory.distance = field.number("distance", trajectory.distance);
    if (!(trajectory.distance >= 0)) field.at("distance").fail("expected a distance of 0 m or more");
  } else if (type == "waypoints") {
    field.allowOnly({"type", "points"});
    trajectory.kind = TrajectorySpec::Kind::Waypoints;
    const JsonField points = field.at("points");
    if (points.size() == 0) points.fail("expected at least one waypoint");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const JsonField point = points.at(i);
      point.allowOnly({"t", "position", "rotation"});
      TrajectorySpec::Waypoint w;
      w.time = point.at("t").number();
      w.position = toVec3(point.at("position").vec3());
      w.rotation = vec3Or(point, "rotation", {});
      if (!trajectory.waypoints.empty() && !(w.time > trajectory.waypoints.back().time)) {
        point.at("t").fail("expected a time later than the previous waypoint's");
      }
      trajectory.waypoints.push_back(w);
    }
  } else {
    field.allowOnly({"type", "file"});
    trajectory.kind = TrajectorySpec::Kind::Csv;
    const JsonField file = field.at("file");
    trajectory.csvFile = file.string();
    trajectory.waypoints = readCsvTrajectory(file, resolve(baseFolder, trajectory.csvFile));
  }
  return trajectory;
}

SoftBodySpec readSoftBody(const JsonField& field, const std::string& baseFolder) {
  SoftBodySpec soft;
  const std::string mesh = field.at("mesh").oneOf({"ellipsoid", "obj", "sheet"});
  if (mesh == "ellipsoid") {
    field.allowOnly({"mesh", "resolution", "exact_hull", "centre", "radius", "material"});
    soft.mesh = SoftBodySpec::Mesh::Ellipsoid;
    soft.resolution = field.integer("resolution", soft.resolution);
    soft.exactHull = field.boolean("exact_hull", soft.exactHull);
    if (soft.resolution < 4 || soft.resolution > 1 << 20) field.at("resolution").fail("expected 4 to 1048576");
    soft.radius = vec3Or(field, "radius", soft.radius);
    if (!(soft.radius.x > 0 && soft.radius.y > 0 && soft.radius.z > 0)) field.at("radius").fail("expected radii greater than 0 m");
  } else if (mesh == "obj") {
    field.allowOnly({"mesh", "file", "scale", "centre", "material"});
    soft.mesh = SoftBodySpec::Mesh::Obj;
    const JsonField file = field.at("file");
    soft.objFile = file.string();
    soft.scale = field.positive("scale", 1);
    try {
      soft.objMesh = loadObj(resolve(baseFolder, soft.objFile));
    } catch (const Error& error) {
      file.fail(std::string("the soft body's OBJ is unusable: ") + error.what());
    }
  } else {
    field.allowOnly({"mesh", "size", "nodes_per_side", "centre", "material"});
    soft.mesh = SoftBodySpec::Mesh::Sheet;
    soft.sheetSize = field.positive("size", soft.sheetSize);
    soft.nodesPerSide = field.integer("nodes_per_side", soft.nodesPerSide);
    if (soft.nodesPerSide < 2 || soft.nodesPerSide > 1024) field.at("nodes_per_side").fail("expected 2 to 1024");
    soft.pressure = 0;
  }
  soft.centre = vec3Or(field, "centre", soft.centre);
  if (const std::optional<JsonField> material = field.find("material")) {
    material->allowOnly({"mass", "linear_stiffness", "pressure", "friction", "damping"});
    soft.mass = material->positive("mass", soft.mass);
    soft.linearStiffness = material->number("linear_stiffness", soft.linearStiffness);
    if (!(soft.linearStiffness > 0 && soft.linearStiffness <= 1)) material->at("linear_stiffness").fail("expected a value in (0, 1]");
    soft.pressure = material->number("pressure", soft.pressure);
    soft.friction = material->number("friction", soft.friction);
    if (!(soft.friction >= 0 && soft.friction <= 1)) material->at("friction").fail("expected a value in [0, 1]");
    soft.damping = material->number("damping", soft.damping);
    if (!(soft.damping >= 0 && soft.damping < 1)) material->at("damping").fail("expected a value in [0, 1)");
  }
  return soft;
}

// Finds or makes the value a path names, for overrides.
JsonValue& valueAt(JsonValue& root, const std::string& path) {
  JsonValue* value = &root;
  std::size_t at = 0;
  while (at < path.size()) {
    if (path[at] == '[') {
      const std::size_t close = path.find(']', at);
      if (close == std::string::npos) throw Error("override '" + path + "': an unclosed '['");
      const std::string digits = path.substr(at + 1, close - at - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6) {
        throw Error("override '" + path + "': '[" + digits + "]' is not an index");
      }
      const std::size_t index = std::stoul(digits);
      if (value->kind != JsonValue::Kind::Array || index >= value->items.size()) {
        throw Error("override '" + path + "': no item [" + digits + "] there");
      }
      value = &value->items[index];
      at = close + 1;
      if (at < path.size() && path[at] == '.') ++at;
      continue;
    }
    const std::size_t end = path.find_first_of(".[", at);
    const std::string key = path.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (key.empty()) throw Error("override '" + path + "': an empty field name");
    if (value->kind == JsonValue::Kind::Null) value->kind = JsonValue::Kind::Object;
    if (value->kind != JsonValue::Kind::Object) throw Error("override '" + path + "': '" + key + "' is inside a value that is not an object");
    auto member = std::find_if(value->members.begin(), value->members.end(),
                               [&](const auto& m) { return m.first == key; });
    if (member == value->members.end()) {
      value->members.emplace_back(key, JsonValue{});
      member = value->members.end() - 1;
    }
    value = &member->second;
    at = end == std::string::npos ? path.size() : (path[end] == '.' ? end + 1 : end);
  }
  return *value;
}

}  // namespace

const char* algorithmKey(AlgorithmKind kind) {
  switch (kind) {
    case AlgorithmKind::StockA: return "stock-A";
    case AlgorithmKind::StockB: return "stock-B";
    case AlgorithmKind::StockE: return "stock-E";
    case AlgorithmKind::RayOnly: return "ray-only";
    case AlgorithmKind::Paper: return "paper";
    case AlgorithmKind::Discrete: return "discrete";
    case AlgorithmKind::Swept: break;
  }
  return "swept";
}

bool isStock(AlgorithmKind kind) {
  return kind == AlgorithmKind::StockA || kind == AlgorithmKind::StockB || kind == AlgorithmKind::StockE;
}

Pose poseOf(const Vec3& position, const Vec3& rotationDegrees) {
  Pose pose;
  pose.translation = position;
  const double angle = length(rotationDegrees) * kDegrees;
  if (angle > 0) pose.rotation = rotationAboutAxis(normalizedOrZero(rotationDegrees), angle);
  return pose;
}

Override parseOverride(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw Error("override '" + text + "': expected path=value, such as step.dt=1/240");
  }
  return {text.substr(0, equals), text.substr(equals + 1)};
}

SceneSpec parseScene(const std::string& text, const std::string& sourceName, const std::string& baseFolder,
                     const std::vector<Override>& overrides) {
  JsonValue root = parseJson(text, sourceName);
  for (const Override& o : overrides) {
    JsonValue value;
    try {
      value = parseJson(o.value, "override " + o.path);
    } catch (const Error&) {
      value.kind = JsonValue::Kind::String;  // a bare word: algorithm=paper
      value.text = o.value;
    }
    valueAt(root, o.path) = value;
  }

  const JsonField scene(root, "", sourceName);
  scene.allowOnly({"name", "description", "step", "gravity", "ground", "soft", "tools", "algorithm", "thintool"});
  SceneSpec spec;
  spec.sourcePath = sourceName;
  spec.name = scene.string("name", "scene");
  if (scene.has("description")) scene.at("description").string();
  if (const std::optional<JsonField> step = scene.find("step")) {
    step->allowOnly({"dt", "substeps", "settle", "duration", "hold"});
    if (step->has("dt")) spec.timeStep = timeStepOf(step->at("dt"));
    spec.substeps = step->integer("substeps", spec.substeps);
    if (spec.substeps < 1 || spec.substeps > 1000) step->at("substeps").fail("expected 1 to 1000");
    spec.settleSeconds = step->number("settle", spec.settleSeconds);
    if (!(spec.settleSeconds >= 0)) step->at("settle").fail("expected 0 s or more");
    spec.duration = step->number("duration", spec.duration);
    if (!(spec.duration >= 0)) step->at("duration").fail("expected 0 s (until the trajectories end) or more");
    spec.holdSeconds = step->number("hold", spec.holdSeconds);
    if (!(spec.holdSeconds >= 0)) step->at("hold").fail("expected 0 s or more");
  }
  spec.gravity = vec3Or(scene, "gravity", spec.gravity);
  spec.ground = scene.boolean("ground", spec.ground);
  spec.soft = readSoftBody(scene.at("soft"), baseFolder);

  const JsonField tools = scene.at("tools");
  if (tools.size() == 0) tools.fail("expected at least one tool");
  for (std::size_t i = 0; i < tools.size(); ++i) {
    const JsonField tool = tools.at(i);
    tool.allowOnly({"name", "shape", "trajectory"});
    ToolSpec spec_;
    spec_.name = tool.string("name", "tool " + std::to_string(i));
    readPieces(tool.at("shape"), baseFolder, spec_.pieces, false);
    spec_.trajectory = readTrajectory(tool.at("trajectory"), baseFolder);
    spec.tools.push_back(std::move(spec_));
  }

  if (scene.has("algorithm")) {
    const std::string key =
        scene.at("algorithm").oneOf({"stock-A", "stock-B", "stock-E", "ray-only", "paper", "swept", "discrete"});
    for (AlgorithmKind kind : {AlgorithmKind::StockA, AlgorithmKind::StockB, AlgorithmKind::StockE,
                               AlgorithmKind::RayOnly, AlgorithmKind::Paper, AlgorithmKind::Swept,
                               AlgorithmKind::Discrete}) {
      if (key == algorithmKey(kind)) spec.algorithm = kind;
    }
  }
  if (const std::optional<JsonField> options = scene.find("thintool")) {
    options->allowOnly({"force", "friction", "last_word", "holds", "energy_guard"});
    spec.force = options->boolean("force", spec.force);
    if (options->has("friction")) spec.friction = options->boolean("friction", false);
    spec.lastWord = options->boolean("last_word", spec.lastWord);
    spec.holds = options->boolean("holds", spec.holds);
    spec.energyGuard = options->boolean("energy_guard", spec.energyGuard);
  }
  if (spec.duration == 0) {
    double end = 0;
    for (const ToolSpec& tool : spec.tools) end = std::max(end, endTime(tool.trajectory));
    spec.duration = end + spec.holdSeconds;
    if (!(spec.duration > 0)) scene.fail("the scene lasts 0 s: give step.duration, step.hold or a trajectory that moves");
  }
  if (spec.duration / spec.timeStep > 1e7) scene.at("step").fail("more than 10 million steps");
  return spec;
}

SceneSpec loadScene(const std::string& path, const std::vector<Override>& overrides) {
  return parseScene(readTextFile(path), path, folderOf(path), overrides);
}

ConvexSolid solidOf(const ToolPieceSpec& piece) {
  return piece.kind == ToolPieceSpec::Kind::Box ? ConvexSolid::box(piece.halfExtents) : piece.hull;
}

double endTime(const TrajectorySpec& trajectory) {
  if (trajectory.kind == TrajectorySpec::Kind::ConstantVelocity) return trajectory.distance / trajectory.speed;
  return trajectory.waypoints.empty() ? 0 : trajectory.waypoints.back().time;
}

Pose poseAt(const TrajectorySpec& trajectory, double time) {
  if (trajectory.kind == TrajectorySpec::Kind::ConstantVelocity) {
    const double travelled = trajectory.speed * std::clamp(time, 0.0, endTime(trajectory));
    return poseOf(trajectory.start + trajectory.direction * travelled, trajectory.rotation);
  }
  const std::vector<TrajectorySpec::Waypoint>& points = trajectory.waypoints;
  if (time <= points.front().time) return poseOf(points.front().position, points.front().rotation);
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (time <= points[i].time) {
      const double s = (time - points[i - 1].time) / (points[i].time - points[i - 1].time);
      return poseOf(points[i - 1].position + (points[i].position - points[i - 1].position) * s,
                    points[i - 1].rotation + (points[i].rotation - points[i - 1].rotation) * s);
    }
  }
  return poseOf(points.back().position, points.back().rotation);
}

}  // namespace thintool::eval
