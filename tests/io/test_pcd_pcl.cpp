// Our PCD files against PCL's, the reference implementation of the format: PCL reads what we
// write (ascii and binary, organized with NaN holes), and we read what PCL writes, including
// binary_compressed files whose LZF stream uses back references.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <string>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class PcdAgainstPcl : public IoTest, public ::testing::WithParamInterface<io::Encoding> {};

TEST_P(PcdAgainstPcl, PclReadsWhatWeWrite) {
  const io::PointCloud written = withIntensities(organizedCloudWithHoles());
  const std::string path = pathOf("ours.pcd");
  io::writePointCloud(path, written, GetParam());

  pcl::PointCloud<pcl::PointXYZINormal> read;
  ASSERT_EQ(pcl::io::loadPCDFile(path, read), 0);
  EXPECT_EQ(read.width, 4u);
  EXPECT_EQ(read.height, 3u);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    const pcl::PointXYZINormal& p = read[i];
    if (!written.points[i].allFinite()) {
      EXPECT_TRUE(std::isnan(p.x)) << "pixel " << i;
      continue;
    }
    // Ascii is the shortest text that reads back to the same float: exact in both encodings.
    EXPECT_EQ(Eigen::Vector3f(p.x, p.y, p.z), written.points[i]) << i;
    EXPECT_EQ(Eigen::Vector3f(p.normal_x, p.normal_y, p.normal_z), written.normals[i]) << i;
    EXPECT_EQ(p.intensity, written.intensities[i]) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdAgainstPcl, ::testing::Values(io::Encoding::Ascii, io::Encoding::Binary));

// A cloud whose columns repeat: LZF codes the repeats as back references, short and long.
pcl::PointCloud<pcl::PointNormal> repetitiveCloud() {
  constexpr std::uint32_t kWidth = 40, kHeight = 25;
  pcl::PointCloud<pcl::PointNormal> cloud;
  for (std::uint32_t row = 0; row < kHeight; ++row) {
    for (std::uint32_t column = 0; column < kWidth; ++column) {
      pcl::PointNormal p;
      p.x = 0.001f * static_cast<float>(column % 7);
      p.y = 0.002f * static_cast<float>(row);
      p.z = (column + row) % 11 == 0 ? std::nanf("") : 0.5f;
      p.normal_x = 0.0f;
      p.normal_y = column % 2 == 0 ? 0.6f : 0.0f;
      p.normal_z = column % 2 == 0 ? 0.8f : 1.0f;
      cloud.push_back(p);
    }
  }
  cloud.width = kWidth;  // push_back made it one row
  cloud.height = kHeight;
  cloud.is_dense = false;
  return cloud;
}

TEST_F(IoTest, WeReadPclsBinaryCompressedFiles) {
  const pcl::PointCloud<pcl::PointNormal> written = repetitiveCloud();
  const std::string path = pathOf("pcl.pcd");
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(path, written), 0);

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_EQ(read.width, 40);
  EXPECT_EQ(read.height, 25);
  ASSERT_EQ(read.size(), written.size());
  ASSERT_TRUE(read.hasNormals());
  for (std::size_t i = 0; i < written.size(); ++i) {
    const pcl::PointNormal& p = written[i];
    if (std::isnan(p.z)) {
      EXPECT_TRUE(std::isnan(read.points[i].z())) << i;
      continue;
    }
    EXPECT_EQ(read.points[i], Eigen::Vector3f(p.x, p.y, p.z)) << i;
    EXPECT_EQ(read.normals[i], Eigen::Vector3f(p.normal_x, p.normal_y, p.normal_z)) << i;
  }
}

}  // namespace
}  // namespace binpick::test
