// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Triangle meshes from Wavefront OBJ files, read with tinyobjloader (Debian's
/// libtinyobjloader-dev) and then checked, because the library accepts what a simulation cannot
/// use: a file with no face, an index past the vertex list, a coordinate that is not a finite
/// number. Polygons are fanned into triangles; normals, texture coordinates, groups and materials
/// are ignored.

#include "GroundTruth.h"

#include <string>
#include <vector>

namespace thintool::eval {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

/// Throws thintool::Error naming the file and the problem (with tinyobjloader's line where it
/// gives one).
TriangleMesh loadObj(const std::string& path);
/// The same for OBJ text held in memory; sourceName names it in errors.
TriangleMesh parseObj(const std::string& text, const std::string& sourceName);

}  // namespace thintool::eval
