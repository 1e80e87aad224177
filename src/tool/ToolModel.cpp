// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/core/Error.h>
#include <thintool/geometry/RayTriangle.h>
#include <thintool/tool/ToolModel.h>

#include <algorithm>
#include <cmath>
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

// Splits every hull triangle through the midpoint of its longest edge until no edge exceeds
// spacing, and puts a node at each piece's centroid.
void sampleTriangleCentroids(ToolModel& model, const SamplingSettings& sampling, Real spacing) {
  // A hair of slack so that an edge of exactly `spacing` is not split again by rounding.
  const Real spacingSquared = spacing * spacing * (1 + 1e-9);
  std::vector<std::array<Vec3, 3>> pending;
  for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
    const auto& tri = model.mesh.triangles[t];
    const Vec3 normal = model.planes[t].normal;
    pending.push_back({model.mesh.vertices[tri[0]], model.mesh.vertices[tri[1]], model.mesh.vertices[tri[2]]});
    while (!pending.empty()) {
      const std::array<Vec3, 3> piece = pending.back();
      pending.pop_back();
      int longest = 0;
      Real longestSquared = -1;
      for (int k = 0; k < 3; ++k) {
        const Real edgeSquared = lengthSquared(piece[(k + 1) % 3] - piece[k]);
        if (edgeSquared > longestSquared) {
          longestSquared = edgeSquared;
          longest = k;
        }
      }
      if (longestSquared > spacingSquared) {
        const Vec3& a = piece[longest];
        const Vec3& b = piece[(longest + 1) % 3];
        const Vec3& c = piece[(longest + 2) % 3];
        const Vec3 middle = (a + b) * Real(0.5);
        pending.push_back({a, middle, c});
        pending.push_back({middle, b, c});
        continue;
      }
      const Index node = model.nodeCount();
      if (node >= sampling.maxNodes) {
        throwTooManyNodes(sampling, spacing);
      }
      addNode(model, (piece[0] + piece[1] + piece[2]) / 3, normal);
      addPatchTriangle(model, node, piece[0], piece[1], piece[2]);
    }
  }
}

// Ref. [3]: a regular grid of cells on the two faces across the box's thinnest axis.
void sampleBoxFaceGrid(ToolModel& model, const SamplingSettings& sampling, Real spacing) {
  Vec3 half;
  Vec3 centre;
  if (!detectBox(model.mesh, half, centre)) {
    throw Error("sampling layout BoxFaceGrid needs a box-shaped piece; use TriangleCentroids for other shapes");
  }
  int thin = 0;
  if (half.y < half[thin]) thin = 1;
  if (half.z < half[thin]) thin = 2;
  const int axisU = (thin + 1) % 3;
  const int axisV = (thin + 2) % 3;
  const Index cellsU = static_cast<Index>(std::max<Real>(1, std::ceil(2 * half[axisU] / spacing)));
  const Index cellsV = static_cast<Index>(std::max<Real>(1, std::ceil(2 * half[axisV] / spacing)));
  if (Real(cellsU) * Real(cellsV) * 2 > Real(sampling.maxNodes)) {
    throwTooManyNodes(sampling, spacing);
  }
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
  if (!(settings.sampling.spacing >= 0) || !std::isfinite(settings.sampling.spacing)) {
    problem << "sampling.spacing must be a finite length >= 0 (0 = automatic), got " << settings.sampling.spacing;
  } else if (settings.sampling.maxNodes == 0) {
    problem << "sampling.maxNodes must be at least 1";
  } else if (!(settings.association.maxRayLength >= 0) || !std::isfinite(settings.association.maxRayLength)) {
    problem << "association.maxRayLength must be a finite length >= 0 (0 = automatic), got "
            << settings.association.maxRayLength;
  } else if (!(settings.probeDepth >= 0) || !std::isfinite(settings.probeDepth)) {
    problem << "probeDepth must be a finite length >= 0 (0 = automatic), got " << settings.probeDepth;
  }
  if (!problem.str().empty()) {
    throw Error(problem.str());
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
  model.bounds = bounds(mesh);
  model.thickness = thicknessAcrossFaces(mesh, model.planes);

  const Vec3 extent = model.bounds.extent();
  const Real largestExtent = std::max({extent.x, extent.y, extent.z});
  model.spacing = settings.sampling.spacing > 0 ? settings.sampling.spacing : largestExtent / kAutoSpacingDivisor;

  if (settings.sampling.layout == SamplingLayout::BoxFaceGrid) {
    sampleBoxFaceGrid(model, settings.sampling, model.spacing);
  } else {
    sampleTriangleCentroids(model, settings.sampling, model.spacing);
  }

  const Real probeDepth = settings.probeDepth > 0 ? settings.probeDepth : model.thickness;
  model.probeLengths.resize(model.nodeCount());
  std::vector<Aabb> rayBoxes(model.nodeCount());
  for (Index i = 0; i < model.nodeCount(); ++i) {
    const Real through = exitDistance(model.planes, model.positions[i], -model.normals[i]);
    model.probeLengths[i] = std::min(through, probeDepth);
    rayBoxes[i] = Aabb::fromPoints(model.positions[i], model.positions[i] - model.normals[i] * model.probeLengths[i]);
  }
  model.rayTree.build(rayBoxes);

  if (settings.association.enabled) {
    const Real maxLength = settings.association.maxRayLength > 0 ? settings.association.maxRayLength
                                                                  : kAutoAssociationFactor * model.thickness;
    associate(model, maxLength);
  } else {
    model.partners.assign(model.nodeCount(), kInvalidIndex);
    model.oppositeBegin.assign(model.nodeCount() + 1, 0);
  }
  return model;
}

}  // namespace thintool
