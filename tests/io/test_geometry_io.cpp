// The public entry points across formats: dispatch, what each function accepts, and the failures
// every reader shares (missing, empty, garbage, unknown extension), plus writer refusals.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class GeometryIo : public IoTest {};

const char* const kExtensions[] = {".ply", ".pcd", ".stl", ".obj"};

TEST_F(GeometryIo, MissingFileIsNamed) {
  for (const char* extension : kExtensions) {
    const std::string path = pathOf(std::string("missing") + extension);
    EXPECT_TRUE(failsWith([&] { io::readModelGeometry(path); }, path, "does not exist")) << extension;
  }
}

TEST_F(GeometryIo, DirectoryIsNotAFile) {
  const std::string path = pathOf("folder.ply");
  std::filesystem::create_directory(path);
  EXPECT_TRUE(failsWith([&] { io::readModelGeometry(path); }, path, "not a regular file"));
}

TEST_F(GeometryIo, EmptyFileIsRejectedInEveryFormat) {
  for (const char* extension : kExtensions) {
    const std::string path = writeFile(std::string("empty") + extension, "");
    EXPECT_TRUE(failsWith([&] { io::readModelGeometry(path); }, path, "the file is empty")) << extension;
  }
}

TEST_F(GeometryIo, BinaryGarbageIsRejectedInEveryFormat) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    for (const char* extension : kExtensions) {
      const std::string path =
          writeFile("garbage" + std::to_string(seed) + extension, garbageBytes(1000 + 997 * seed, seed));
      EXPECT_TRUE(failsWith([&] { io::readModelGeometry(path); }, path, "")) << extension << " " << seed;
    }
  }
}

TEST_F(GeometryIo, UnknownOrMissingExtensionIsNamed) {
  const std::string unknown = writeFile("scan.xyz", "0 0 0\n");
  EXPECT_TRUE(failsWith([&] { io::readModelGeometry(unknown); }, unknown, "unknown file extension '.xyz'"));
  const std::string none = writeFile("scan", "0 0 0\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(none); }, none, "no file extension"));
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(pathOf("out.xyz"), awkwardCloud()); }, pathOf("out.xyz"),
                        "unknown file extension"));
}

TEST_F(GeometryIo, ExtensionIsCaseInsensitive) {
  const std::string path = pathOf("UPPER.PLY");
  io::writePointCloud(path, awkwardCloud());
  EXPECT_EQ(io::readPointCloud(path).size(), 3u);
}

TEST_F(GeometryIo, ModelGeometryGivesMeshAndItsVerticesForMeshFiles) {
  io::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  for (const char* extension : {".ply", ".stl", ".obj"}) {
    const std::string path = pathOf(std::string("triangle") + extension);
    io::writeMesh(path, mesh);
    const io::ModelGeometry geometry = io::readModelGeometry(path);
    EXPECT_TRUE(geometry.hasMesh()) << extension;
    EXPECT_EQ(geometry.mesh.triangles.size(), 1u) << extension;
    EXPECT_EQ(geometry.cloud.points, geometry.mesh.vertices) << extension;
  }
}

TEST_F(GeometryIo, ModelGeometryGivesOnlyACloudForCloudFiles) {
  for (const char* extension : {".ply", ".pcd"}) {
    const std::string path = pathOf(std::string("cloud") + extension);
    io::writePointCloud(path, organizedCloudWithHoles());
    const io::ModelGeometry geometry = io::readModelGeometry(path);
    EXPECT_FALSE(geometry.hasMesh()) << extension;
    EXPECT_EQ(geometry.cloud.size(), 12u) << extension;
    EXPECT_TRUE(geometry.cloud.isOrganized()) << extension;
  }
}

TEST_F(GeometryIo, FunctionsRefuseFormatsTheyDoNotRead) {
  const std::string pcd = pathOf("cloud.pcd");
  io::writePointCloud(pcd, awkwardCloud());
  EXPECT_TRUE(failsWith([&] { io::readMesh(pcd); }, pcd, "holds no faces"));

  io::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  const std::string stl = pathOf("mesh.stl");
  io::writeMesh(stl, mesh);
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(stl); }, stl, "readPointCloud reads .ply and .pcd"));
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(stl, awkwardCloud()); }, stl, "writePointCloud writes"));
  EXPECT_TRUE(failsWith([&] { io::writeMesh(pcd, mesh); }, pcd, "writeMesh writes"));
}

TEST_F(GeometryIo, MeshWithOnlyDegenerateFacesIsRejected) {
  const std::string path = writeFile("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "all 2 faces have zero area"));
}

TEST_F(GeometryIo, MeshWithNonFiniteVertexIsRejected) {
  const std::string path = writeFile("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
  EXPECT_TRUE(failsWith([&] { io::readMesh(path); }, path, "vertex 2 is not finite"));
}

TEST_F(GeometryIo, WritersRefuseWhatReadersWouldReject) {
  io::PointCloud withNan = awkwardCloud();
  withNan.points[1].y() = NAN;
  const std::string cloudPath = pathOf("nan.ply");
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(cloudPath, withNan); }, cloudPath, "point 1 is not finite"));
  EXPECT_FALSE(std::filesystem::exists(cloudPath));

  EXPECT_TRUE(failsWith([&] { io::writePointCloud(cloudPath, io::PointCloud{}); }, cloudPath, "no points"));

  io::TriangleMesh broken;
  broken.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  broken.triangles = {{0, 1, 3}};
  const std::string meshPath = pathOf("broken.stl");
  EXPECT_TRUE(failsWith([&] { io::writeMesh(meshPath, broken); }, meshPath, "triangle 0 refers to vertex 3"));
}

TEST_F(GeometryIo, WritingIntoMissingDirectoryIsNamed) {
  for (const char* extension : {".ply", ".pcd"}) {
    const std::string path = pathOf(std::string("no/such/dir/cloud") + extension);
    EXPECT_TRUE(failsWith([&] { io::writePointCloud(path, awkwardCloud()); }, path, "")) << extension;
  }
}

TEST_F(GeometryIo, ConcurrentReadsAgree) {
  const std::string path = pathOf("shared.ply");
  io::writePointCloud(path, organizedCloudWithHoles());
  std::vector<std::size_t> sizes(4, 0);
  std::vector<std::thread> readers;
  for (std::size_t t = 0; t < sizes.size(); ++t) {
    readers.emplace_back([&, t] {
      for (int repeat = 0; repeat < 20; ++repeat) sizes[t] = io::readPointCloud(path).size();
    });
  }
  for (std::thread& reader : readers) reader.join();
  for (std::size_t size : sizes) EXPECT_EQ(size, 12u);
}

}  // namespace
}  // namespace binpick::test
