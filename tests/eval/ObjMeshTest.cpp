// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// OBJ loading: polygons fanned into triangles, relative indices, and a clear error for every
// malformed file that tinyobjloader lets through or rejects.

#include <ObjMesh.h>

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <string>

namespace thintool::eval {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseObj(text, "test.obj");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(ObjMesh, ReadsTrianglesAndFansPolygons) {
  const TriangleMesh mesh = parseObj(
      "# a unit square and a triangle\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
      "f 1//1 2//1 3//1 4//1\n"
      "f -4 -3 -2\n",  // relative indices: the last four vertices
      "square.obj");
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.triangles[2], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.vertices[2].y, 1);
}

TEST(ObjMesh, AFileWithoutFacesIsAnError) {
  EXPECT_NE(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\n").find("test.obj: no face"), std::string::npos);
  EXPECT_NE(errorOf("").find("no face"), std::string::npos);
}

TEST(ObjMesh, AnIndexPastTheVertexListNamesTheFace) {
  const std::string error = errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  EXPECT_NE(error.find("test.obj"), std::string::npos) << error;
  EXPECT_NE(error.find("face 2"), std::string::npos) << error;
}

TEST(ObjMesh, AnIndexBeforeTheFirstVertexIsAnError) {
  EXPECT_FALSE(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n").empty());
  EXPECT_FALSE(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").empty());
}

TEST(ObjMesh, AnOverflowingCoordinateIsAnError) {
  const std::string error = errorOf("v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(error.find("test.obj"), std::string::npos) << error;
}

TEST(ObjMesh, AFaceWithTwoCornersIsAnError) { EXPECT_FALSE(errorOf("v 0 0 0\nv 1 0 0\nf 1 2\n").empty()); }

TEST(ObjMesh, AMissingFileIsAnError) {
  try {
    loadObj("/nonexistent/mesh.obj");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/mesh.obj: cannot read"), std::string::npos);
  }
}

}  // namespace
}  // namespace thintool::eval
