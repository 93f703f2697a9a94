// OBJ: every face-corner form, negative indices, polygons, and bad indices with line numbers.
#include <gtest/gtest.h>

#include <string>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class Obj : public IoTest {};

TEST_F(Obj, ReadsAllCornerFormsNegativeIndicesAndQuads) {
  const std::string path = writeFile("shapes.obj",
                                     "# a square and a pyramid tip\n"
                                     "mtllib shapes.mtl\n"
                                     "o square\n"
                                     "v 0 0 0\n"
                                     "v 1 0 0 1.0\n"
                                     "v 1 1 0 0.5 0.5 0.5\n"
                                     "v 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                     "vn 0 0 1\n"
                                     "usemtl red\n"
                                     "s off\n"
                                     "f 1/1/1 2/2/1 3/3/1 4/4/1   # quad, v/vt/vn\n"
                                     "v 0.5 0.5 1\n"
                                     "g tip\n"
                                     "f -5//1 -4//1 -1//1\n"
                                     "f 2/2 3/3 5/1\n"
                                     "f\t3 4 5\r\n"
                                     "l 1 2\n");
  const io::TriangleMesh mesh = io::readMesh(path);
  ASSERT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.vertices[4], Eigen::Vector3f(0.5f, 0.5f, 1));
  const std::vector<Eigen::Vector3i> expected = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}};
  EXPECT_EQ(mesh.triangles, expected);
}

TEST_F(Obj, RoundTripKeepsMesh) {
  io::TriangleMesh written;
  written.vertices = {{0.1f, 0.2f, 0.3f}, {1e-20f, -4.0f, 5.5f}, {7, 8, 9.125f}, {-1, -2, -3}};
  written.triangles = {{0, 1, 2}, {3, 2, 1}};
  const std::string path = pathOf("mesh.obj");
  io::writeMesh(path, written);
  const io::ModelGeometry read = io::readModelGeometry(path);
  ASSERT_EQ(read.mesh.vertices.size(), written.vertices.size());
  for (std::size_t i = 0; i < written.vertices.size(); ++i) {
    EXPECT_TRUE(sameBits(read.mesh.vertices[i], written.vertices[i])) << i;
  }
  EXPECT_EQ(read.mesh.triangles, written.triangles);
}

TEST_F(Obj, RejectsIndexBeyondTheVerticesWithItsLine) {
  const std::string path = writeFile("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 9\n");
  EXPECT_TRUE(
      failsWith([&] { io::readMesh(path); }, path, "line 6: face refers to vertex 9 but the file has 4 vertices"));
}

TEST_F(Obj, RejectsNegativeIndexBeforeFirstVertex) {
  const std::string path = writeFile("negative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "line 3: face refers to vertex -3"));
}

TEST_F(Obj, RejectsZeroIndexAndShortFaces) {
  const std::string zero = writeFile("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(zero); }, zero, "line 4: face corner '0'"));
  const std::string shortFace = writeFile("short.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(shortFace); }, shortFace, "line 3: face has 2 vertices"));
}

TEST_F(Obj, RejectsBadCoordinate) {
  const std::string path = writeFile("coord.obj", "v 0 0 0\nv 1 zero 0\n");
  EXPECT_TRUE(failsWith([&] { io::readModelGeometry(path); }, path, "line 2: vertex coordinate 'zero'"));
}

TEST_F(Obj, VerticesWithoutFacesAreACloud) {
  const std::string path = writeFile("points.obj", "v 0 0 0\nv 1 0 0\n");
  const io::ModelGeometry geometry = io::readModelGeometry(path);
  EXPECT_FALSE(geometry.hasMesh());
  EXPECT_EQ(geometry.cloud.size(), 2u);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "no faces"));
}

}  // namespace
}  // namespace binpick::test
