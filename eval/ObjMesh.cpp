// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "ObjMesh.h"

#include "Json.h"

#include <thintool/core/Error.h>

#include <tiny_obj_loader.h>


namespace thintool::eval {

namespace {

std::string firstLine(const std::string& message) {
  std::string line = message.substr(0, message.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

TriangleMesh meshFrom(const tinyobj::ObjReader& reader, const std::string& sourceName) {
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  TriangleMesh mesh;
  const std::size_t vertexCount = attrib.vertices.size() / 3;
  mesh.vertices.reserve(vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const Vec3 p{attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]};
    if (!isFinite(p)) {
      throw Error(sourceName + ": vertex " + std::to_string(v + 1) + " is not a finite point");
    }
    mesh.vertices.push_back(p);
  }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
    std::size_t first = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t corners = shape.mesh.num_face_vertices[f];
      if (corners < 3 || first + corners > indices.size()) {
        throw Error(sourceName + ": face " + std::to_string(f + 1) + " of '" + shape.name +
                    "' has fewer than 3 vertices");
      }
      std::vector<int> polygon;
      for (std::size_t k = 0; k < corners; ++k) {
        const int index = indices[first + k].vertex_index;
        if (index < 0 || std::size_t(index) >= vertexCount) {
          throw Error(sourceName + ": face " + std::to_string(f + 1) + " of '" + shape.name +
                      "' names vertex " + std::to_string(index + 1) + " of " + std::to_string(vertexCount));
        }
        polygon.push_back(index);
      }
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
      }
      first += corners;
    }
  }
  if (mesh.triangles.empty()) {
    throw Error(sourceName + ": no face (an OBJ mesh needs 'f' lines)");
  }
  return mesh;
}

}  // namespace

TriangleMesh parseObj(const std::string& text, const std::string& sourceName) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fanned here, after the indices are checked
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    throw Error(sourceName + ": " + firstLine(reader.Error()));
  }
  return meshFrom(reader, sourceName);
}

TriangleMesh loadObj(const std::string& path) { return parseObj(readTextFile(path), path); }

}  // namespace thintool::eval
