// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The tool model: sample nodes on a convex tool piece, their association across the piece, and
/// the short rays each node casts into soft tissue. Built once per piece, in the piece's frame.
///
/// Source: Fazioli et al. (the paper, §III.B–C) and Fukuhara et al., ROBOMECH J. 1:6 (2014),
/// its ref. [3]. Deviations:
/// - Sampling. The paper puts one node at each hull triangle's centroid, with the triangle's
///   normal (kept as SamplingLayout::HullTriangleCentroids). A box has 12 triangles, far too few
///   for a plate pressing a ball whose faces are 0.45 m wide, and splitting its long, thin side
///   triangles makes slivers by the hundred. By default each planar face is instead cut by a grid
///   of cells no wider than `spacing`, aligned with the face's longest edge, and a node stands at
///   the centroid of each cell's part of the face, its "patch" (SamplingLayout::FacePatches). On
///   a box face this is the grid of ref. [3], which is also kept as SamplingLayout::BoxFaceGrid
///   (the two large faces only).
/// - Association. As in §III.C: a ray from each node along its inward normal, limited in length,
///   finds the patch it leaves the piece through, and that patch's node becomes the partner. Pairs
///   are not assumed mutual. The paper's "vector of indices that cannot collide" is built from
///   each node's opposite set: its partner plus every node that chose it as partner, so check 1
///   blocks both directions of a non-mutual pair (the cross-check of §III.C).
/// - Probe length. A node looks for soft faces only inside the piece, up to the piece's width
///   along its normal and at most `probeDepth`: a face deeper than that belongs to the nodes on
///   the other side.

#include "geometry/AabbTree.h"
#include "geometry/ConvexMesh.h"
#include "geometry/PointGrid.h"

#include <thintool/core/Math.h>
#include <thintool/tool/ToolModelSettings.h>

#include <array>
#include <optional>
#include <vector>

namespace thintool {

/// A unit axis with the extent of the piece's hull along it.
struct AxisExtent {
  Vec3 axis;
  Real low = 0;
  Real high = 0;
};

/// Sample nodes of one convex piece, in the piece's frame. Immutable once built.
struct ToolModel {
  ConvexMesh mesh;
  std::vector<Plane> planes;
  /// Each plane's normal, made unit, with the hull's extent along it (a zero axis where the normal
  /// is too short to make unit): the piece's own axes in every separating-axis test against a
  /// soft triangle, the same for all of them.
  std::vector<AxisExtent> planeAxes;
  Aabb bounds;
  Real thickness = 0;  ///< smallest width across the face normals (m)
  Real spacing = 0;    ///< the sampling spacing used (m)

  // Per node.
  std::vector<Vec3> positions;    ///< on the piece's surface
  std::vector<Vec3> normals;      ///< unit, outward
  std::vector<Real> probeLengths; ///< how far inside the piece the node's ray reaches (m)
  std::vector<Index> partners;    ///< associated node, or kInvalidIndex
  std::vector<Index> oppositeBegin;  ///< CSR offsets into opposites (size nodeCount + 1)
  std::vector<Index> opposites;      ///< partner plus the nodes that chose this node

  // The patch each node stands for: triangles tagged with their node.
  std::vector<std::array<Vec3, 3>> patchTriangles;
  std::vector<Index> patchOwners;

  /// Boxes around each node's inward ray, for finding the rays a soft face can meet.
  AabbTree rayTree;

  /// The tool's points for swept detection: its sample nodes, then the hull's corners, and a grid
  /// over them. Point i < nodeCount() is node i; the others are mesh vertex i - nodeCount().
  std::vector<Vec3> points;
  PointGrid pointGrid;

  /// Edges of the mesh between faces of different planes (the diagonals of a flat face are not
  /// edges of the solid), as mesh vertex pairs: what can slice between soft nodes.
  std::vector<std::array<Index, 2>> featureEdges;
  std::vector<Aabb> featureEdgeBoxes;  ///< one per feature edge
  std::vector<std::array<Vec3, 2>> featureEdgeNormals;  ///< one per feature edge: its two faces' outward normals
  /// The feature edges' directions (corner to corner), each once, up to sign: a box's twelve edges
  /// have three. Separating axes built on two equal directions are the same axis.
  std::vector<Vec3> featureEdgeDirections;

  Index mutualPairs = 0;    ///< nodes whose partner chose them back
  Index unpairedNodes = 0;  ///< nodes whose association ray found nothing within its length

  Index nodeCount() const { return static_cast<Index>(positions.size()); }
};

/// Builds the model of one convex piece; throws thintool::Error naming the problem.
ToolModel buildToolModel(const ConvexMesh& mesh, const ToolModelSettings& settings);

/// Half extents and centre of mesh when it is an axis-aligned box in its frame.
bool detectBox(const ConvexMesh& mesh, Vec3& outHalfExtents, Vec3& outCentre);

}  // namespace thintool
