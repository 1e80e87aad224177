// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/RayTriangle.h"
#include "tool/ToolModel.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace thintool {

namespace {

constexpr Real kAutoSpacingDivisor = 8;       // spacing = largest extent / 8
constexpr Real kAutoAssociationFactor = 1.5;  // association ray = 1.5 × thickness
constexpr Real kBoxCornerTolerance = 1e-9;    // relative to the box diagonal

void addNode(ToolModel& model, const Vec3& position, const Vec3& normal) {
  model.positions.push_back(position);
  model.normals.push_back(normal);
}

void addPatchTriangle(ToolModel& model, Index node, const Vec3& a, const Vec3& b, const Vec3& c) {
  model.patchTriangles.push_back({a, b, c});
  model.patchOwners.push_back(node);
}

void throwTooManyNodes(const SamplingSettings& sampling, Real spacing) {
  std::ostringstream message;
  message << "sampling spacing " << spacing << " m would create more than " << sampling.maxNodes
          << " nodes; raise sampling.spacing or sampling.maxNodes";
  throw Error(message.str());
}

// Paper §III.C as written: one node at each hull triangle's centroid.
void sampleHullTriangleCentroids(ToolModel& model, const SamplingSettings& sampling) {
  for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
    const auto& tri = model.mesh.triangles[t];
    const Vec3& a = model.mesh.vertices[tri[0]];
    const Vec3& b = model.mesh.vertices[tri[1]];
    const Vec3& c = model.mesh.vertices[tri[2]];
    const Index node = model.nodeCount();
    if (node >= sampling.maxNodes) {
      throwTooManyNodes(sampling, 0);
    }
    addNode(model, (a + b + c) / 3, model.planes[t].normal);
    addPatchTriangle(model, node, a, b, c);
  }
}

struct Point2 {
  Real u = 0;
  Real v = 0;
};

// Sutherland–Hodgman: keeps the part of polygon with coordinate `axis` (0: u, 1: v) on the side
// `sign`·(x - bound) <= 0. A triangle clipped by a rectangle has at most 7 corners.
int clipPolygon(const Point2* in, int count, int axis, Real bound, Real sign, Point2* out) {
  auto coordinate = [axis](const Point2& p) { return axis == 0 ? p.u : p.v; };
  int written = 0;
  for (int k = 0; k < count; ++k) {
    const Point2& from = in[k];
    const Point2& to = in[(k + 1) % count];
    const Real dFrom = sign * (coordinate(from) - bound);
    const Real dTo = sign * (coordinate(to) - bound);
    if (dFrom <= 0) {
      out[written++] = from;
    }
    if ((dFrom < 0 && dTo > 0) || (dFrom > 0 && dTo < 0)) {
      const Real s = dFrom / (dFrom - dTo);
      out[written++] = {from.u + s * (to.u - from.u), from.v + s * (to.v - from.v)};
    }
  }
  return written;
}

// Every planar face is cut by a grid of cells at most `spacing` wide, aligned with its longest
// edge; a node stands at the centroid of each cell's part of the face.
void sampleFacePatches(ToolModel& model, const SamplingSettings& sampling, Real spacing) {
  const ConvexMesh& mesh = model.mesh;
  const Real size = length(model.bounds.extent());
  std::vector<char> grouped(mesh.triangles.size(), 0);
  for (std::size_t first = 0; first < mesh.triangles.size(); ++first) {
    if (grouped[first]) {
      continue;
    }
    // The face: every triangle on the first one's plane.
    const Plane plane = model.planes[first];
    std::vector<std::size_t> face;
    for (std::size_t t = first; t < mesh.triangles.size(); ++t) {
      const Plane& other = model.planes[t];
      if (!grouped[t] && dot(other.normal, plane.normal) > 1 - 1e-9 &&
          std::abs(other.offset - plane.offset) <= 1e-9 * size) {
        grouped[t] = 1;
        face.push_back(t);
      }
    }

    // Face frame: u along the longest boundary edge, v = n × u, origin at a vertex. An edge
    // whose reverse belongs to the same face is a diagonal of the triangulation, not a side.
    auto isInterior = [&](Index from, Index to) {
      for (std::size_t t : face) {
        const auto& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k) {
          if (tri[k] == to && tri[(k + 1) % 3] == from) {
            return true;
          }
        }
      }
      return false;
    };
    Vec3 axisU;
    Real longest = -1;
    for (std::size_t t : face) {
      for (int k = 0; k < 3; ++k) {
        const Index from = mesh.triangles[t][k];
        const Index to = mesh.triangles[t][(k + 1) % 3];
        const Vec3 edge = mesh.vertices[to] - mesh.vertices[from];
        if (lengthSquared(edge) > longest && !isInterior(from, to)) {
          longest = lengthSquared(edge);
          axisU = normalizedOrZero(edge - plane.normal * dot(edge, plane.normal));
        }
      }
    }
    const Vec3 axisV = cross(plane.normal, axisU);
    const Vec3 origin = mesh.vertices[mesh.triangles[face.front()][0]];
    auto toPlane = [&](const Vec3& p) { return Point2{dot(p - origin, axisU), dot(p - origin, axisV)}; };
    auto toSpace = [&](const Point2& p) { return origin + axisU * p.u + axisV * p.v; };

    Point2 low{std::numeric_limits<Real>::max(), std::numeric_limits<Real>::max()};
    Point2 high{-std::numeric_limits<Real>::max(), -std::numeric_limits<Real>::max()};
    for (std::size_t t : face) {
      for (Index corner : mesh.triangles[t]) {
        const Point2 p = toPlane(mesh.vertices[corner]);
        low = {std::min(low.u, p.u), std::min(low.v, p.v)};
        high = {std::max(high.u, p.u), std::max(high.v, p.v)};
      }
    }
    // The slack keeps a side of exactly n·spacing from getting n + 1 cells through rounding.
    // Counted in Real first: a huge face at a fine spacing has more cells than an Index holds.
    const Real realCellsU = std::max<Real>(1, std::ceil((high.u - low.u) / spacing - 1e-9));
    const Real realCellsV = std::max<Real>(1, std::ceil((high.v - low.v) / spacing - 1e-9));
    if (!(Real(model.nodeCount()) + realCellsU * realCellsV <= Real(sampling.maxNodes))) {
      throwTooManyNodes(sampling, spacing);
    }
    const auto cellsU = static_cast<Index>(realCellsU);
    const auto cellsV = static_cast<Index>(realCellsV);
    const Real cellU = (high.u - low.u) / cellsU;
    const Real cellV = (high.v - low.v) / cellsV;
    const Real negligibleArea = 1e-12 * cellU * cellV;

    for (Index i = 0; i < cellsU; ++i) {
      for (Index j = 0; j < cellsV; ++j) {
        const Real u0 = low.u + i * cellU;
        const Real v0 = low.v + j * cellV;
        Real area = 0;
        Point2 moment;
        const Index node = model.nodeCount();
        for (std::size_t t : face) {
          Point2 a[8];
          Point2 b[8];
          for (int k = 0; k < 3; ++k) {
            a[k] = toPlane(mesh.vertices[mesh.triangles[t][k]]);
          }
          int count = clipPolygon(a, 3, 0, u0, -1, b);
          count = clipPolygon(b, count, 0, u0 + cellU, 1, a);
          count = clipPolygon(a, count, 1, v0, -1, b);
          count = clipPolygon(b, count, 1, v0 + cellV, 1, a);
          for (int k = 1; k + 1 < count; ++k) {
            const Real piece = ((a[k].u - a[0].u) * (a[k + 1].v - a[0].v) - (a[k + 1].u - a[0].u) * (a[k].v - a[0].v)) / 2;
            if (piece <= negligibleArea) {
              continue;
            }
            area += piece;
            moment.u += piece * (a[0].u + a[k].u + a[k + 1].u) / 3;
            moment.v += piece * (a[0].v + a[k].v + a[k + 1].v) / 3;
            addPatchTriangle(model, node, toSpace(a[0]), toSpace(a[k]), toSpace(a[k + 1]));
          }
        }
        if (area > 0) {
          addNode(model, toSpace({moment.u / area, moment.v / area}), plane.normal);
        }
      }
    }
  }
}

// Ref. [3]: a regular grid of cells on the two faces across the box's thinnest axis.
void sampleBoxFaceGrid(ToolModel& model, const SamplingSettings& sampling, Real spacing) {
  Vec3 half;
  Vec3 centre;
  if (!detectBox(model.mesh, half, centre)) {
    throw Error("sampling layout BoxFaceGrid needs a box-shaped piece; use FacePatches for other shapes");
  }
  int thin = 0;
  if (half.y < half[thin]) thin = 1;
  if (half.z < half[thin]) thin = 2;
  const int axisU = (thin + 1) % 3;
  const int axisV = (thin + 2) % 3;
  const Real realCellsU = std::max<Real>(1, std::ceil(2 * half[axisU] / spacing - 1e-9));
  const Real realCellsV = std::max<Real>(1, std::ceil(2 * half[axisV] / spacing - 1e-9));
  if (!(realCellsU * realCellsV * 2 <= Real(sampling.maxNodes))) {
    throwTooManyNodes(sampling, spacing);
  }
  const auto cellsU = static_cast<Index>(realCellsU);
  const auto cellsV = static_cast<Index>(realCellsV);
  const Real cellU = 2 * half[axisU] / cellsU;
  const Real cellV = 2 * half[axisV] / cellsV;
  for (int side = -1; side <= 1; side += 2) {
    Vec3 normal;
    normal[thin] = side;
    for (Index i = 0; i < cellsU; ++i) {
      for (Index j = 0; j < cellsV; ++j) {
        auto corner = [&](Real du, Real dv) {
          Vec3 p = centre;
          p[thin] += side * half[thin];
          p[axisU] += -half[axisU] + du * cellU;
          p[axisV] += -half[axisV] + dv * cellV;
          return p;
        };
        const Index node = model.nodeCount();
        addNode(model, corner(i + Real(0.5), j + Real(0.5)), normal);
        // Both triangles counter-clockwise seen along the normal, so the patch faces outwards.
        const Vec3 c00 = corner(i, j), c10 = corner(i + 1, j), c11 = corner(i + 1, j + 1), c01 = corner(i, j + 1);
        if (side > 0) {
          addPatchTriangle(model, node, c00, c10, c11);
          addPatchTriangle(model, node, c00, c11, c01);
        } else {
          addPatchTriangle(model, node, c00, c11, c10);
          addPatchTriangle(model, node, c00, c01, c11);
        }
      }
    }
  }
}

// Each node's inward ray, limited to maxLength, finds the patch it leaves through (paper §III.C).
void associate(ToolModel& model, Real maxLength) {
  const Index nodeCount = model.nodeCount();
  model.partners.assign(nodeCount, kInvalidIndex);

  std::vector<Aabb> patchBoxes;
  patchBoxes.reserve(model.patchTriangles.size());
  for (const auto& tri : model.patchTriangles) {
    Aabb box = Aabb::fromPoints(tri[0], tri[1]);
    box.include(tri[2]);
    patchBoxes.push_back(box);
  }
  AabbTree patchTree;
  patchTree.build(patchBoxes);

  for (Index i = 0; i < nodeCount; ++i) {
    const Vec3 origin = model.positions[i];
    const Vec3 delta = model.normals[i] * -maxLength;
    Real closest = 2;  // beyond the segment's end
    patchTree.querySegment(SegmentSlab(origin, delta), [&](Index patch) {
      const Index owner = model.patchOwners[patch];
      // Only a face turned away from the node can be where its ray leaves a convex piece; this
      // also keeps the node's own face and its coplanar neighbours out.
      if (owner == i || dot(model.normals[owner], model.normals[i]) >= 0) {
        return;
      }
      const auto& tri = model.patchTriangles[patch];
      const SegmentTriangleHit hit = intersectSegmentTriangle(origin, delta, tri[0], tri[1], tri[2]);
      if (hit.hit && hit.t < closest) {
        closest = hit.t;
        model.partners[i] = owner;
      }
    });
  }

  // Opposite sets in CSR form: the partner, and every node that chose this one.
  std::vector<std::vector<Index>> opposite(nodeCount);
  for (Index i = 0; i < nodeCount; ++i) {
    const Index partner = model.partners[i];
    if (partner == kInvalidIndex) {
      ++model.unpairedNodes;
      continue;
    }
    opposite[i].push_back(partner);
    opposite[partner].push_back(i);
    if (model.partners[partner] == i) {
      ++model.mutualPairs;
    }
  }
  model.oppositeBegin.assign(nodeCount + 1, 0);
  for (Index i = 0; i < nodeCount; ++i) {
    auto& set = opposite[i];
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    model.oppositeBegin[i + 1] = model.oppositeBegin[i] + static_cast<Index>(set.size());
  }
  model.opposites.reserve(model.oppositeBegin.back());
  for (const auto& set : opposite) {
    model.opposites.insert(model.opposites.end(), set.begin(), set.end());
  }
}

void checkSettings(const ToolModelSettings& settings) {
  std::ostringstream problem;
  // A length the user gave: finite and positive. Left empty, the model picks it.
  const auto badLength = [](const std::optional<Real>& length) {
    return length.has_value() && !(std::isfinite(*length) && *length > 0);
  };
  if (badLength(settings.sampling.spacing)) {
    problem << "sampling.spacing must be a finite length > 0 (empty: automatic), got " << *settings.sampling.spacing;
  } else if (settings.sampling.maxNodes == 0) {
    problem << "sampling.maxNodes must be at least 1";
  } else if (badLength(settings.association.maxRayLength)) {
    problem << "association.maxRayLength must be a finite length > 0 (empty: automatic), got "
            << *settings.association.maxRayLength;
  } else if (badLength(settings.probeDepth)) {
    problem << "probeDepth must be a finite length > 0 (empty: automatic), got " << *settings.probeDepth;
  }
  if (!problem.str().empty()) {
    throw Error(problem.str());
  }
}

// Edges shared by two triangles whose planes differ, with those two planes' normals.
void findFeatureEdges(const ConvexMesh& mesh, const std::vector<Plane>& planes, ToolModel& model) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index from = mesh.triangles[t][k];
      const Index to = mesh.triangles[t][(k + 1) % 3];
      if (from > to) {
        continue;  // each edge once: the neighbour has it the other way round
      }
      for (std::size_t n = 0; n < mesh.triangles.size(); ++n) {
        const auto& other = mesh.triangles[n];
        const bool shares = (other[0] == to && other[1] == from) || (other[1] == to && other[2] == from) ||
                            (other[2] == to && other[0] == from);
        if (shares) {
          if (dot(planes[t].normal, planes[n].normal) < 1 - 1e-9) {
            model.featureEdges.push_back({from, to});
            model.featureEdgeNormals.push_back({planes[t].normal, planes[n].normal});
          }
          break;
        }
      }
    }
  }
}

}  // namespace

bool detectBox(const ConvexMesh& mesh, Vec3& outHalfExtents, Vec3& outCentre) {
  if (mesh.vertices.size() != 8) {
    return false;
  }
  const Aabb box = bounds(mesh);
  const Real tolerance = kBoxCornerTolerance * length(box.extent());
  int cornersSeen = 0;
  for (const Vec3& v : mesh.vertices) {
    int corner = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(v[axis] - box.max[axis]) <= tolerance) {
        corner |= 1 << axis;
      } else if (std::abs(v[axis] - box.min[axis]) > tolerance) {
        return false;
      }
    }
    cornersSeen |= 1 << corner;
  }
  if (cornersSeen != 0xff) {
    return false;
  }
  outHalfExtents = box.extent() * Real(0.5);
  outCentre = box.center();
  return true;
}

ToolModel buildToolModel(const ConvexMesh& mesh, const ToolModelSettings& settings) {
  checkSettings(settings);
  const std::string meshProblem = validateConvexMesh(mesh);
  if (!meshProblem.empty()) {
    throw Error("invalid convex shape: " + meshProblem);
  }

  ToolModel model;
  model.mesh = mesh;
  model.planes = facePlanes(mesh);
  for (const Plane& plane : model.planes) {
    AxisExtent extent;
    const Real normalLength = length(plane.normal);
    if (normalLength > Real(1e-12)) {
      extent.axis = plane.normal / normalLength;
      projectedInterval(extent.axis, mesh.vertices.data(), mesh.vertices.size(), extent.low, extent.high);
    }
    model.planeAxes.push_back(extent);
  }
  model.bounds = bounds(mesh);
  model.thickness = thicknessAcrossFaces(mesh, model.planes);
  findFeatureEdges(mesh, model.planes, model);
  for (const auto& edge : model.featureEdges) {
    model.featureEdgeBoxes.push_back(Aabb::fromPoints(mesh.vertices[edge[0]], mesh.vertices[edge[1]]));
    const Vec3 direction = mesh.vertices[edge[1]] - mesh.vertices[edge[0]];
    const auto same = [&](const Vec3& known) { return known == direction || known == -direction; };
    if (std::none_of(model.featureEdgeDirections.begin(), model.featureEdgeDirections.end(), same)) {
      model.featureEdgeDirections.push_back(direction);
    }
  }

  const Vec3 extent = model.bounds.extent();
  const Real largestExtent = std::max({extent.x, extent.y, extent.z});
  model.spacing = settings.sampling.spacing.value_or(largestExtent / kAutoSpacingDivisor);

  if (settings.sampling.layout == SamplingLayout::BoxFaceGrid) {
    sampleBoxFaceGrid(model, settings.sampling, model.spacing);
  } else if (settings.sampling.layout == SamplingLayout::HullTriangleCentroids) {
    sampleHullTriangleCentroids(model, settings.sampling);
  } else {
    sampleFacePatches(model, settings.sampling, model.spacing);
  }

  const Real probeDepth = settings.probeDepth.value_or(model.thickness);
  model.probeLengths.resize(model.nodeCount());
  std::vector<Aabb> rayBoxes(model.nodeCount());
  for (Index i = 0; i < model.nodeCount(); ++i) {
    const Real through = exitDistance(model.planes, model.positions[i], -model.normals[i]);
    model.probeLengths[i] = std::min(through, probeDepth);
    rayBoxes[i] = Aabb::fromPoints(model.positions[i], model.positions[i] - model.normals[i] * model.probeLengths[i]);
  }
  model.rayTree.build(rayBoxes);

  model.points = model.positions;
  model.points.insert(model.points.end(), mesh.vertices.begin(), mesh.vertices.end());
  model.pointGrid.build(model.points);

  if (settings.association.enabled) {
    const Real maxLength = settings.association.maxRayLength.value_or(kAutoAssociationFactor * model.thickness);
    associate(model, maxLength);
  } else {
    model.partners.assign(model.nodeCount(), kInvalidIndex);
    model.oppositeBegin.assign(model.nodeCount() + 1, 0);
  }
  return model;
}

}  // namespace thintool
