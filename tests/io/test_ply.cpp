// PLY: round trips in both encodings, hand-made files exercising the header grammar, and the
// corrupt files a reader meets in practice.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class Ply : public IoTest {};

class PlyRoundTrip : public IoTest, public ::testing::WithParamInterface<io::Encoding> {};

TEST_P(PlyRoundTrip, OrganizedCloudKeepsGridHolesAndNormals) {
  const io::PointCloud written = organizedCloudWithHoles();
  const std::string path = pathOf("organized.ply");
  io::writePointCloud(path, written, GetParam());

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_EQ(read.width, 4);
  EXPECT_EQ(read.height, 3);
  ASSERT_EQ(read.size(), written.size());
  ASSERT_TRUE(read.hasNormals());
  for (std::size_t i = 0; i < written.size(); ++i) {
    if (!written.points[i].allFinite()) {
      EXPECT_TRUE(read.points[i].array().isNaN().all()) << "pixel " << i;
      continue;
    }
    // Binary stores the float bits; ascii writes the shortest text that parses back identically.
    EXPECT_TRUE(sameBits(read.points[i], written.points[i])) << "point " << i;
    EXPECT_TRUE(sameBits(read.normals[i], written.normals[i])) << "normal " << i;
  }
}

TEST_P(PlyRoundTrip, UnorganizedCloudKeepsAwkwardValues) {
  const io::PointCloud written = awkwardCloud();
  const std::string path = pathOf("awkward.ply");
  io::writePointCloud(path, written, GetParam());

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_FALSE(read.isOrganized());
  EXPECT_FALSE(read.hasNormals());
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const float expected = written.points[i][axis];
      EXPECT_NEAR(read.points[i][axis], expected, 1e-6f * std::abs(expected)) << i << "," << axis;
    }
  }
}

// Binary keeps every bit, the NaN payloads of invalid pixels included; ascii writes "nan" there.
TEST_P(PlyRoundTrip, OrganizedCloudKeepsIntensitiesAfterNormals) {
  const io::PointCloud written = withIntensities(organizedCloudWithHoles());
  const std::string path = pathOf("intensities.ply");
  io::writePointCloud(path, written, GetParam());
  EXPECT_NE(readFile(path).find("property float nz\nproperty float intensity\n"), std::string::npos);

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_EQ(read.width, 4);
  ASSERT_TRUE(read.hasNormals());
  ASSERT_TRUE(read.hasIntensities());
  for (std::size_t i = 0; i < written.size(); ++i) {
    if (GetParam() == io::Encoding::Binary || written.points[i].allFinite()) {
      EXPECT_TRUE(sameBits(read.intensities[i], written.intensities[i])) << "pixel " << i;
    } else {
      EXPECT_TRUE(std::isnan(read.intensities[i])) << "pixel " << i;
    }
    if (written.points[i].allFinite()) {
      EXPECT_TRUE(sameBits(read.normals[i], written.normals[i])) << "normal " << i;
    }
  }
}

TEST_P(PlyRoundTrip, UnorganizedCloudKeepsIntensitiesWithoutNormals) {
  const io::PointCloud written = withIntensities(awkwardCloud());
  const std::string path = pathOf("intensities.ply");
  io::writePointCloud(path, written, GetParam());
  EXPECT_NE(readFile(path).find("property float z\nproperty float intensity\n"), std::string::npos);

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_FALSE(read.hasNormals());
  ASSERT_TRUE(read.hasIntensities());
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_TRUE(sameBits(read.intensities[i], written.intensities[i])) << i;
    EXPECT_TRUE(sameBits(read.points[i], written.points[i])) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Ply, PlyRoundTrip, ::testing::Values(io::Encoding::Binary, io::Encoding::Ascii),
                         [](const ::testing::TestParamInfo<io::Encoding>& encoding) {
                           return encoding.param == io::Encoding::Binary ? "Binary" : "Ascii";
                         });

TEST_F(Ply, MeshRoundTripKeepsVerticesAndTriangles) {
  io::TriangleMesh written;
  written.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  written.triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::string path = pathOf("mesh.ply");
  io::writeMesh(path, written);

  const io::TriangleMesh read = io::readMesh(path);
  ASSERT_EQ(read.vertices.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_TRUE(sameBits(read.vertices[i], written.vertices[i]));
  ASSERT_EQ(read.triangles.size(), 2u);
  EXPECT_EQ(read.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(read.triangles[1], Eigen::Vector3i(0, 2, 3));
}

// Big-endian doubles, a uchar intensity and a skipped list property on the vertices, faces
// declared as
// `list uint8 uint vertex_index` with a quad, and unknown elements before and after the faces.
// The list makes vertex records vary in size, so this takes the record-by-record binary path.
std::string bigEndianDoublePly() {
  std::string bytes =
      "ply\n"
      "format binary_big_endian 1.0\n"
      "comment hand made\n"
      "element vertex 4\n"
      "property double x\n"
      "property uchar intensity\n"
      "property double y\n"
      "property double z\n"
      "property list uchar short tags\n"
      "element edge 1\n"
      "property int vertex1\n"
      "property int vertex2\n"
      "element face 2\n"
      "property uchar flags\n"
      "property list uint8 uint vertex_index\n"
      "element material 1\n"
      "property float shininess\n"
      "end_header\n";
  const double corners[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 1.5}};
  for (int v = 0; v < 4; ++v) {
    appendBytes(bytes, corners[v][0], true);
    appendBytes<std::uint8_t>(bytes, static_cast<std::uint8_t>(200 + v));
    appendBytes(bytes, corners[v][1], true);
    appendBytes(bytes, corners[v][2], true);
    appendBytes<std::uint8_t>(bytes, static_cast<std::uint8_t>(v));  // v tags of 2 bytes each
    for (int tag = 0; tag < v; ++tag) appendBytes<std::int16_t>(bytes, 7, true);
  }
  appendBytes<std::int32_t>(bytes, 0, true);
  appendBytes<std::int32_t>(bytes, 1, true);
  appendBytes<std::uint8_t>(bytes, 0);  // face 0: flags, then a quad
  appendBytes<std::uint8_t>(bytes, 4);
  for (std::uint32_t index : {0u, 1u, 2u, 3u}) appendBytes(bytes, index, true);
  appendBytes<std::uint8_t>(bytes, 0);  // face 1: a triangle
  appendBytes<std::uint8_t>(bytes, 3);
  for (std::uint32_t index : {0u, 2u, 1u}) appendBytes(bytes, index, true);
  appendBytes(bytes, 0.5f, true);
  return bytes;
}

TEST_F(Ply, ReadsBigEndianDoublesSkippingOtherPropertiesAndElements) {
  const std::string path = writeFile("big_endian.ply", bigEndianDoublePly());
  const io::ModelGeometry geometry = io::readModelGeometry(path);

  ASSERT_TRUE(geometry.hasMesh());
  ASSERT_EQ(geometry.mesh.vertices.size(), 4u);
  EXPECT_EQ(geometry.mesh.vertices[3], Eigen::Vector3f(0, 2, 1.5f));
  EXPECT_EQ(geometry.mesh.vertices[1], Eigen::Vector3f(2, 0, 0));
  ASSERT_EQ(geometry.mesh.triangles.size(), 3u);  // the quad becomes a fan of two
  EXPECT_EQ(geometry.mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(geometry.mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(geometry.mesh.triangles[2], Eigen::Vector3i(0, 2, 1));
  EXPECT_EQ(geometry.cloud.points, geometry.mesh.vertices);
  EXPECT_EQ(geometry.cloud.intensities, (std::vector<float>{200, 201, 202, 203}));
}

// Float x, y, z records in either byte order and in any property order: the records of a
// little-endian x, y, z file are copied whole, every other layout is decoded value by value.
TEST_F(Ply, ReadsFloatCoordinatesInEveryByteOrderAndPropertyOrder) {
  const Eigen::Vector3f points[3] = {{1.5f, -2.25f, 3.0f}, {NAN, NAN, NAN}, {-0.001f, 1e6f, 0.0f}};
  for (const bool big_endian : {false, true}) {
    for (const std::string order : {"xyz", "zxy"}) {
      std::string bytes =
          std::string("ply\nformat binary_") + (big_endian ? "big" : "little") + "_endian 1.0\nelement vertex 3\n";
      for (const char axis : order) bytes += std::string("property float ") + axis + "\n";
      bytes += "obj_info organized 3 1\nend_header\n";
      for (const Eigen::Vector3f& point : points) {
        for (const char axis : order) appendBytes(bytes, point[axis - 'x'], big_endian);
      }
      const io::PointCloud cloud = io::readPointCloud(writeFile("cloud.ply", bytes));
      ASSERT_EQ(cloud.size(), 3u) << order << big_endian;
      for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(sameBits(cloud.points[i], points[i])) << order << big_endian << i;
    }
  }
}

TEST_F(Ply, ReadsAsciiWithCrLfCommentsQuadsAndNormalisesNormals) {
  const std::string path = writeFile("ascii.ply",
                                     "ply\r\n"
                                     "format ascii 1.0\r\n"
                                     "comment exported by hand\r\n"
                                     "obj_info some free text\r\n"
                                     "element vertex 4\r\n"
                                     "property float x\r\nproperty float y\r\nproperty float z\r\n"
                                     "property float nx\r\nproperty float ny\r\nproperty float nz\r\n"
                                     "property uchar red\r\n"
                                     "element face 1\r\n"
                                     "property list uchar int vertex_indices\r\n"
                                     "end_header\r\n"
                                     "0 0 0 0 0 2 255\r\n"
                                     "1 0 0 0 0 1 255\r\n"
                                     "1 1 0 0 3 4 255\r\n"
                                     "+0 1e0 -0.0 0 0 1 255\r\n"
                                     "4 0 1 2 3\r\n");
  const io::ModelGeometry geometry = io::readModelGeometry(path);
  ASSERT_EQ(geometry.mesh.triangles.size(), 2u);
  ASSERT_TRUE(geometry.cloud.hasNormals());
  EXPECT_TRUE(geometry.cloud.normals[0].isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(geometry.cloud.normals[2].isApprox(Eigen::Vector3f(0, 0.6f, 0.8f)));
  EXPECT_EQ(geometry.cloud.points[3], Eigen::Vector3f(0, 1, 0));
}

// Intensities are converted to float as stored, not rescaled to 0..1.
TEST_F(Ply, ReadsUcharIntensityAsciiAndBinary) {
  const std::string header =
      "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar intensity\nend_header\n";
  const std::string ascii = writeFile("ascii.ply", "ply\nformat ascii 1.0\n" + header + "0 0 0 0\n1 2 3 255\n");
  std::string bytes = "ply\nformat binary_little_endian 1.0\n" + header;
  for (int v = 0; v < 2; ++v) {
    for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, static_cast<float>(v + axis));
    appendBytes<std::uint8_t>(bytes, static_cast<std::uint8_t>(v * 255));
  }
  const std::string binary = writeFile("binary.ply", bytes);

  for (const std::string& path : {ascii, binary}) {
    const io::PointCloud cloud = io::readPointCloud(path);
    EXPECT_EQ(cloud.intensities, (std::vector<float>{0, 255})) << path;
  }
}

// Where the property sits in the record does not matter.
TEST_F(Ply, ReadsDoubleIntensityBeforeTheCoordinates) {
  const std::string header =
      "element vertex 2\nproperty double intensity\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const std::string ascii = writeFile("ascii.ply", "ply\nformat ascii 1.0\n" + header + "0.7 0 0 0\n0.25 1 2 3\n");
  std::string bytes = "ply\nformat binary_big_endian 1.0\n" + header;
  for (int v = 0; v < 2; ++v) {
    appendBytes(bytes, v == 0 ? 0.7 : 0.25, true);
    for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, static_cast<float>(v + axis), true);
  }
  const std::string binary = writeFile("binary.ply", bytes);

  for (const std::string& path : {ascii, binary}) {
    const io::PointCloud cloud = io::readPointCloud(path);
    EXPECT_EQ(cloud.intensities, (std::vector<float>{0.7f, 0.25f})) << path;
    EXPECT_EQ(cloud.points[1], Eigen::Vector3f(1, 2, 3)) << path;
  }
}

TEST_F(Ply, RejectsNanIntensityOfAValidPoint) {
  const std::string path = writeFile("nan_intensity.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 2\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "property float intensity\nend_header\n"
                                     "0 0 0 0.5\n1 0 0 nan\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "intensity of point 1 is not finite (nan)"));
}

TEST_F(Ply, RefusesToWriteWrongIntensityCountOrNanIntensity) {
  io::PointCloud cloud = withIntensities(awkwardCloud());
  cloud.intensities.pop_back();
  const std::string path = pathOf("bad.ply");
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(path, cloud); }, path, "2 intensities for 3 points"));
  cloud = withIntensities(awkwardCloud());
  cloud.intensities[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(path, cloud, io::Encoding::Ascii); }, path,
                        "intensity of point 0 is not finite"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

std::string binaryCloudPly(const std::string& extraHeader, int vertices) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\n" + extraHeader + "element vertex " +
                      std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (int v = 0; v < vertices; ++v) {
    for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, static_cast<float>(v + axis));
  }
  return bytes;
}

TEST_F(Ply, RejectsTruncatedBinaryBody) {
  std::string bytes = binaryCloudPly("", 10);
  bytes.resize(bytes.size() - 5);
  const std::string path = writeFile("truncated.ply", bytes);
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "truncated"));
}

TEST_F(Ply, RejectsAbsurdVertexCountWithoutAllocating) {
  for (const char* format : {"binary_little_endian", "ascii"}) {
    const std::string path =
        writeFile(std::string(format) + ".ply", std::string("ply\nformat ") + format +
                                                    " 1.0\nelement vertex 1000000000000\n"
                                                    "property float x\nproperty float y\nproperty float z\n"
                                                    "end_header\n0 0 0\n");
    EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "1000000000000")) << format;
  }
}

TEST_F(Ply, RejectsHugeFaceListWithoutAllocating) {
  std::string bytes = binaryCloudPly("", 3);
  bytes.insert(bytes.find("end_header"), "element face 1\nproperty list uint int vertex_indices\n");
  appendBytes<std::uint32_t>(bytes, 4000000000u);
  const std::string path = writeFile("huge_face.ply", bytes);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "face 0 has a list of 4000000000 items"));
}

TEST_F(Ply, RejectsFaceIndexOutOfRange) {
  const std::string path = writeFile("bad_index.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 4\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "element face 2\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 9\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "face 1 refers to vertex 9 but the file has 4 vertices"));
}

TEST_F(Ply, RejectsNanInUnorganizedCloudNamingThePoint) {
  const std::string path = writeFile("nan.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "end_header\n0 0 0\n1 0 0\n1 nan 0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "point 2 is not finite"));
}

TEST_F(Ply, RejectsInfEvenInOrganizedCloud) {
  std::string bytes = binaryCloudPly("obj_info organized 2 1\n", 2);
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(bytes.data() + bytes.size() - sizeof(float), &inf, sizeof(float));
  const std::string path = writeFile("inf.ply", bytes);
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "point 1 is not finite"));
}

TEST_F(Ply, RejectsZeroNormalNamingThePoint) {
  const std::string path = writeFile("zero_normal.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 2\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "property float nx\nproperty float ny\nproperty float nz\n"
                                     "end_header\n0 0 0 0 0 1\n1 0 0 0 0 0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "normal of point 1 is zero"));
}

TEST_F(Ply, RejectsOrganizedSizeThatDoesNotMatchVertexCount) {
  const std::string path = writeFile("grid.ply", binaryCloudPly("obj_info organized 3 3\n", 4));
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "organized 3 x 3"));
}

TEST_F(Ply, RejectsMalformedHeaders) {
  const std::string unknownType =
      writeFile("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flaot x\nend_header\n0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(unknownType); }, unknownType, "unknown property type 'flaot'"));

  const std::string noEnd = writeFile("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(noEnd); }, noEnd, "end_header"));

  const std::string noZ = writeFile("no_z.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float "
                                    "x\nproperty float y\nend_header\n0 0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(noZ); }, noZ, "no 'z' property"));

  const std::string notPly = writeFile("not.ply", "solid cube\nendsolid\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(notPly); }, notPly, "not a PLY file"));
}

TEST_F(Ply, RejectsBadAsciiValueWithItsLine) {
  const std::string path = writeFile("bad_value.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 2\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "end_header\n0 0 0\n1 zero 0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "line 9 (vertex 1): 'zero' is not a number"));
}

// Token-based reading would silently shift every later value by one.
TEST_F(Ply, RejectsAsciiRecordsWithTooManyOrTooFewValues) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n";
  const std::string extra = writeFile("extra.ply", header + "0 0 0\n1 0 0 5\n0 1 0\n");
  EXPECT_TRUE(
      failsWith([&] { io::readPointCloud(extra); }, extra, "line 9 (vertex 1): more values than the header declares"));
  const std::string missing = writeFile("missing.ply", header + "0 0 0\n1 0\n0 1 0\n0 0 1\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(missing); }, missing,
                        "line 9 (vertex 1): fewer values than the header declares"));
}

TEST_F(Ply, CloudFileHasNoMeshAndReadMeshSaysSo) {
  const std::string path = writeFile("cloud.ply", binaryCloudPly("", 3));
  const io::ModelGeometry geometry = io::readModelGeometry(path);
  EXPECT_FALSE(geometry.hasMesh());
  EXPECT_EQ(geometry.cloud.size(), 3u);
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "no faces"));
}

}  // namespace
}  // namespace binpick::test
