// validateCloud / validateMesh: the rules every reader and writer applies.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(Validate, OrganizedCloudMayHoldNanPixels) {
  EXPECT_NO_THROW(io::validateCloud(organizedCloudWithHoles(), "scan"));
}

TEST(Validate, UnorganizedCloudMayNotHoldNan) {
  io::PointCloud cloud = awkwardCloud();
  cloud.points[2].z() = kNan;
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "point 2 is not finite"));
}

TEST(Validate, OrganizedCloudMayNotHoldInf) {
  io::PointCloud cloud = organizedCloudWithHoles();
  cloud.points[7].x() = kInf;
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "point 7 is not finite"));
}

// The clouds are scanned as raw float bits first: every kind of non-finite value, in any
// coordinate of any point, the first and the last included, is still found and named.
TEST(Validate, EveryNonFiniteCoordinateIsFoundWhereverItIs) {
  const float signalling = std::numeric_limits<float>::signaling_NaN();
  const io::PointCloud organized = organizedCloudWithHoles(), unorganized = awkwardCloud();
  for (const io::PointCloud* base : {&organized, &unorganized}) {
    const bool is_organized = base == &organized;
    std::vector<float> bad{kInf, -kInf};
    if (!is_organized) bad.insert(bad.end(), {kNan, -kNan, signalling});
    for (const std::size_t index : {std::size_t{0}, base->size() / 2, base->size() - 1}) {
      for (int axis = 0; axis < 3; ++axis) {
        for (const float value : bad) {
          io::PointCloud cloud = *base;
          if (is_organized) cloud.points[index] = Eigen::Vector3f(0.1f, 0.2f, 0.9f);  // not a hole
          cloud.points[index][axis] = value;
          EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan",
                                "point " + std::to_string(index) + " is not finite"))
              << (is_organized ? "organized" : "unorganized") << ", axis " << axis << ", value " << value;
        }
      }
    }
  }
}

TEST(Validate, GridMustMatchPointCount) {
  io::PointCloud cloud = organizedCloudWithHoles();
  cloud.width = 5;
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "width 5 x height 3"));
}

TEST(Validate, NormalsMustMatchAndBeFiniteForValidPoints) {
  io::PointCloud cloud = organizedCloudWithHoles();
  cloud.normals.pop_back();
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "11 normals for 12 points"));

  cloud = organizedCloudWithHoles();
  cloud.normals[3] = Eigen::Vector3f(kNan, 0, 1);
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "normal of point 3 is not finite"));
}

TEST(Validate, IntensitiesOfInvalidPixelsMayBeNan) {
  const io::PointCloud cloud = withIntensities(organizedCloudWithHoles());
  ASSERT_TRUE(std::isnan(cloud.intensities[5]));
  EXPECT_NO_THROW(io::validateCloud(cloud, "scan"));
}

TEST(Validate, IntensitiesMustMatchAndBeFiniteForValidPoints) {
  io::PointCloud cloud = withIntensities(organizedCloudWithHoles());
  cloud.intensities.pop_back();
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "11 intensities for 12 points"));

  cloud = withIntensities(awkwardCloud());
  cloud.intensities.push_back(0.5f);
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "4 intensities for 3 points"));

  cloud = withIntensities(organizedCloudWithHoles());
  cloud.intensities[3] = kNan;
  EXPECT_TRUE(failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "intensity of point 3 is not finite (nan)"));

  cloud = withIntensities(awkwardCloud());
  cloud.intensities[1] = -kInf;
  EXPECT_TRUE(
      failsWith([&] { io::validateCloud(cloud, "scan"); }, "scan", "intensity of point 1 is not finite (-inf)"));
}

TEST(Validate, MeshIndicesAndVerticesAreChecked) {
  io::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {2, 1, -1}};
  EXPECT_TRUE(failsWith([&] { io::validateMesh(mesh, "part"); }, "part",
                        "triangle 1 refers to vertex -1 but the mesh has 3 vertices"));
  mesh.triangles.pop_back();
  EXPECT_NO_THROW(io::validateMesh(mesh, "part"));
  mesh.vertices[1].y() = kNan;
  EXPECT_TRUE(failsWith([&] { io::validateMesh(mesh, "part"); }, "part", "vertex 1 is not finite"));
}

}  // namespace
}  // namespace binpick::test
