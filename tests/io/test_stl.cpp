// STL: ascii and binary reading with vertex merging, binary detection by size, round trip.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <set>
#include <string>
#include <tuple>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class Stl : public IoTest {};

// The unit cube as 12 outward-facing triangles.
std::vector<std::array<Eigen::Vector3f, 3>> cubeTriangles() {
  const Eigen::Vector3f c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                            {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::vector<std::array<Eigen::Vector3f, 3>> triangles;
  for (const auto& face : faces) triangles.push_back({c[face[0]], c[face[1]], c[face[2]]});
  return triangles;
}

std::string asciiCube() {
  std::string text = "solid unit cube\n";
  for (const auto& triangle : cubeTriangles()) {
    const Eigen::Vector3f normal = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]).normalized();
    text += "  facet normal " + std::to_string(normal.x()) + " " + std::to_string(normal.y()) + " " +
            std::to_string(normal.z()) + "\n    outer loop\n";
    for (const auto& corner : triangle) {
      text += "      vertex " + std::to_string(corner.x()) + " " + std::to_string(corner.y()) + " " +
              std::to_string(corner.z()) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid unit cube\n";
}

std::string binaryCube(const std::string& header80) {
  std::string bytes = header80;
  bytes.resize(80, ' ');
  const auto triangles = cubeTriangles();
  appendBytes<std::uint32_t>(bytes, static_cast<std::uint32_t>(triangles.size()));
  for (const auto& triangle : triangles) {
    for (int i = 0; i < 3; ++i) appendBytes(bytes, 0.0f);
    for (const auto& corner : triangle) {
      for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, corner[axis]);
    }
    appendBytes<std::uint16_t>(bytes, 0);
  }
  return bytes;
}

double volumeOf(const io::TriangleMesh& mesh) {
  double volume = 0;
  for (const auto& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return volume;
}

// A closed cube with shared vertices: 8 corners, 12 triangles, volume 1 (so winding is kept).
void expectSharedVertexCube(const io::TriangleMesh& mesh) {
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(volumeOf(mesh), 1.0, 1e-6);
}

TEST_F(Stl, AsciiCubeMergesSharedCorners) {
  const std::string path = writeFile("cube.stl", asciiCube());
  expectSharedVertexCube(io::readMesh(path));
}

TEST_F(Stl, BinaryCubeMergesSharedCorners) {
  const std::string path = writeFile("cube.stl", binaryCube("binary cube"));
  expectSharedVertexCube(io::readMesh(path));
}

TEST_F(Stl, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const std::string path = writeFile("solid_header.stl", binaryCube("solid exported by a CAD tool"));
  expectSharedVertexCube(io::readMesh(path));
}

TEST_F(Stl, UppercaseKeywordsAndModelGeometryCloud) {
  std::string text = asciiCube();
  for (const char* keyword : {"solid", "facet", "vertex"}) {
    std::string upper = keyword;
    for (char& c : upper) c = static_cast<char>(std::toupper(c));
    for (std::size_t at = text.find(keyword); at != std::string::npos; at = text.find(keyword, at)) {
      text.replace(at, upper.size(), upper);
    }
  }
  const std::string path = writeFile("upper.stl", text);
  const io::ModelGeometry geometry = io::readModelGeometry(path);
  expectSharedVertexCube(geometry.mesh);
  EXPECT_EQ(geometry.cloud.points, geometry.mesh.vertices);
}

TEST_F(Stl, RoundTripKeepsTriangles) {
  const std::string source = writeFile("source.stl", asciiCube());
  const io::TriangleMesh written = io::readMesh(source);
  const std::string path = pathOf("copy.stl");
  io::writeMesh(path, written);
  EXPECT_NE(readFile(path).rfind("solid", 0), 0u) << "a binary STL must not start with 'solid'";
  const io::TriangleMesh read = io::readMesh(path);
  ASSERT_EQ(read.triangles.size(), written.triangles.size());
  for (std::size_t t = 0; t < read.triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      EXPECT_TRUE(sameBits(read.vertices[read.triangles[t][corner]], written.vertices[written.triangles[t][corner]]));
    }
  }
}

TEST_F(Stl, RejectsTruncatedBinary) {
  std::string bytes = binaryCube("binary cube");
  bytes.resize(bytes.size() - 30);
  const std::string path = writeFile("truncated.stl", bytes);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "claims 12 triangles"));
}

TEST_F(Stl, RejectsTruncatedAscii) {
  std::string text = asciiCube();
  text.resize(text.find("endloop", text.size() / 2));
  const std::string path = writeFile("truncated.stl", text);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "truncated"));
}

TEST_F(Stl, RejectsMisspeltKeywordWithLine) {
  std::string text = asciiCube();
  text.replace(text.find("outer loop"), 10, "outer lop");
  const std::string path = writeFile("typo.stl", text);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "line 3: expected 'loop' but found 'lop'"));
}

TEST_F(Stl, RejectsNanCorner) {
  std::string text = asciiCube();
  text.replace(text.find("vertex 0.000000"), 15, "vertex nan");
  const std::string path = writeFile("nan.stl", text);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "facet 0 has a non-finite vertex"));
}

}  // namespace
}  // namespace binpick::test
