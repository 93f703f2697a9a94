// PCD: round trips, hand-made ascii and binary_compressed files, and the corrupt headers our own
// check must stop before anything is allocated from them. PCL's own reader and writer: test_pcd_pcl.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "binpick/io/geometry_io.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

class Pcd : public IoTest {};

class PcdRoundTrip : public IoTest, public ::testing::WithParamInterface<io::Encoding> {};

TEST_P(PcdRoundTrip, OrganizedCloudKeepsGridHolesAndNormals) {
  const io::PointCloud written = organizedCloudWithHoles();
  const std::string path = pathOf("organized.pcd");
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
    for (int axis = 0; axis < 3; ++axis) {
      const float expected = written.points[i][axis];
      EXPECT_NEAR(read.points[i][axis], expected, 1e-6f * std::abs(expected)) << i;
      EXPECT_NEAR(read.normals[i][axis], written.normals[i][axis], 1e-6f) << i;
    }
    if (GetParam() == io::Encoding::Binary) {
      EXPECT_TRUE(sameBits(read.points[i], written.points[i]));
    }
  }
}

TEST_P(PcdRoundTrip, UnorganizedCloudStaysUnorganized) {
  const io::PointCloud written = awkwardCloud();
  const std::string path = pathOf("awkward.pcd");
  io::writePointCloud(path, written, GetParam());
  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_FALSE(read.isOrganized());
  EXPECT_FALSE(read.hasNormals());
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const float expected = written.points[i][axis];
      EXPECT_NEAR(read.points[i][axis], expected, 1e-6f * std::abs(expected)) << i;
    }
  }
}

// Binary keeps every bit, the NaN payloads of invalid pixels included; ascii writes "nan" there.
TEST_P(PcdRoundTrip, OrganizedCloudKeepsIntensities) {
  const io::PointCloud written = withIntensities(organizedCloudWithHoles());
  const std::string path = pathOf("intensities.pcd");
  io::writePointCloud(path, written, GetParam());
  EXPECT_NE(readFile(path).find("FIELDS x y z normal_x normal_y normal_z intensity\n"), std::string::npos);

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_EQ(read.height, 3);
  ASSERT_TRUE(read.hasNormals());
  ASSERT_TRUE(read.hasIntensities());
  for (std::size_t i = 0; i < written.size(); ++i) {
    if (GetParam() == io::Encoding::Binary) {
      EXPECT_TRUE(sameBits(read.intensities[i], written.intensities[i])) << "pixel " << i;
    } else if (written.points[i].allFinite()) {
      EXPECT_NEAR(read.intensities[i], written.intensities[i], 1e-7f) << "pixel " << i;
    } else {
      EXPECT_TRUE(std::isnan(read.intensities[i])) << "pixel " << i;
    }
  }
}

TEST_P(PcdRoundTrip, UnorganizedCloudKeepsIntensitiesWithoutNormals) {
  const io::PointCloud written = withIntensities(awkwardCloud());
  const std::string path = pathOf("intensities.pcd");
  io::writePointCloud(path, written, GetParam());
  EXPECT_NE(readFile(path).find("FIELDS x y z intensity\n"), std::string::npos);

  const io::PointCloud read = io::readPointCloud(path);
  EXPECT_FALSE(read.hasNormals());
  ASSERT_TRUE(read.hasIntensities());
  for (std::size_t i = 0; i < written.size(); ++i) {
    // 9 significant digits round-trip every float.
    EXPECT_TRUE(sameBits(read.intensities[i], written.intensities[i])) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Pcd, PcdRoundTrip, ::testing::Values(io::Encoding::Binary, io::Encoding::Ascii),
                         [](const ::testing::TestParamInfo<io::Encoding>& encoding) {
                           return encoding.param == io::Encoding::Binary ? "Binary" : "Ascii";
                         });

TEST_F(Pcd, ReadsAsciiWithDoublesExtraFieldsAndNormals) {
  const std::string path = writeFile("extra.pcd",
                                     "# .PCD v0.7 - Point Cloud Data file format\n"
                                     "VERSION 0.7\n"
                                     "FIELDS x y z rgb normal_x normal_y normal_z descriptor\n"
                                     "SIZE 8 8 8 4 4 4 4 4\n"
                                     "TYPE F F F U F F F F\n"
                                     "COUNT 1 1 1 1 1 1 1 3\n"
                                     "WIDTH 2\n"
                                     "HEIGHT 1\n"
                                     "VIEWPOINT 0 0 0 1 0 0 0\n"
                                     "POINTS 2\n"
                                     "DATA ascii\n"
                                     "0.5 -1.25 3 4278190080 0 0 2 1 2 3\n"
                                     "1e-3 2 -0 16711680 0.6 0.8 0 4 5 6\n");
  const io::ModelGeometry geometry = io::readModelGeometry(path);
  EXPECT_FALSE(geometry.hasMesh());
  const io::PointCloud& cloud = geometry.cloud;
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.isOrganized());
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(0.5f, -1.25f, 3));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(1e-3f, 2, 0));
  ASSERT_TRUE(cloud.hasNormals());
  EXPECT_TRUE(cloud.normals[0].isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(cloud.normals[1].isApprox(Eigen::Vector3f(0.6f, 0.8f, 0)));
}

// PCL stores binary_compressed data field by field (all x, then all y, ...) and LZF-compressed;
// one LZF literal run (control byte n-1, then n bytes) is a valid stream for up to 32 bytes.
TEST_F(Pcd, ReadsBinaryCompressed) {
  std::string bytes =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
      "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA binary_compressed\n";
  appendBytes<std::uint32_t>(bytes, 25);
  appendBytes<std::uint32_t>(bytes, 24);
  bytes += static_cast<char>(23);
  for (float value : {1.0f, 4.0f, 2.0f, 5.0f, 3.0f, 6.0f}) appendBytes(bytes, value);
  const std::string path = writeFile("compressed.pcd", bytes);
  const io::PointCloud cloud = io::readPointCloud(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
}

// Intensities are converted to float as stored, not rescaled to 0..1.
TEST_F(Pcd, ReadsIntegerIntensityAsciiAndBinary) {
  const std::string header =
      "VERSION 0.7\nFIELDS intensity x y z\nSIZE 2 4 4 4\nTYPE U F F F\nCOUNT 1 1 1 1\n"
      "WIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  const std::string ascii = writeFile("ascii.pcd", header + "DATA ascii\n0 1 2 3\n65535 4 5 6\n");
  std::string bytes = header + "DATA binary\n";
  for (int v = 0; v < 2; ++v) {
    appendBytes<std::uint16_t>(bytes, static_cast<std::uint16_t>(v * 65535));
    for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, static_cast<float>(3 * v + axis + 1));
  }
  const std::string binary = writeFile("binary.pcd", bytes);

  for (const std::string& path : {ascii, binary}) {
    const io::PointCloud cloud = io::readPointCloud(path);
    EXPECT_EQ(cloud.intensities, (std::vector<float>{0, 65535})) << path;
    EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6)) << path;
  }
}

TEST_F(Pcd, ReadsSignedAndDoubleIntensity) {
  for (const char* sizeAndType : {"8 F", "1 I"}) {
    const std::string type = std::string(sizeAndType).substr(2);
    const std::string header = "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 " + std::string(1, sizeAndType[0]) +
                               "\nTYPE F F F " + type + "\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA binary\n";
    std::string bytes = header;
    for (int axis = 0; axis < 3; ++axis) appendBytes(bytes, static_cast<float>(axis));
    if (type == "F") {
      appendBytes(bytes, 0.7);
    } else {
      appendBytes<std::int8_t>(bytes, -5);
    }
    const std::string path = writeFile("intensity.pcd", bytes);
    EXPECT_EQ(io::readPointCloud(path).intensities.at(0), type == "F" ? 0.7f : -5.0f) << sizeAndType;
  }
}

TEST_F(Pcd, RejectsNanIntensityOfAValidPointAndIntensityWithCount) {
  const std::string nan = writeFile("nan.pcd",
                                    "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                                    "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n0 0 0 nan\n1 1 1 0.5\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(nan); }, nan, "intensity of point 0 is not finite (nan)"));

  const std::string counted =
      writeFile("count.pcd",
                "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 2\n"
                "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n0 0 0 0.5 0.5\n");
  EXPECT_TRUE(
      failsWith([&] { io::readPointCloud(counted); }, counted, "PCD field 'intensity' must be a single number"));
}

TEST_F(Pcd, RefusesToWriteWrongIntensityCount) {
  io::PointCloud cloud = withIntensities(organizedCloudWithHoles());
  cloud.intensities.resize(13, 0.5f);
  const std::string path = pathOf("bad.pcd");
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(path, cloud); }, path, "13 intensities for 12 points"));
}

std::string xyzHeader(const std::string& data, const std::string& size) {
  return "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " + size + "\nHEIGHT 1\nPOINTS " +
         size + "\nDATA " + data + "\n";
}

TEST_F(Pcd, RejectsAbsurdPointCountWithoutAllocating) {
  for (const char* data : {"binary", "ascii"}) {
    const std::string path = writeFile(std::string(data) + ".pcd", xyzHeader(data, "100000000") + "1 2 3\n");
    EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "header claims 100000000 points")) << data;
  }
  const std::string huge = writeFile("huge.pcd", xyzHeader("binary", "1000000000000"));
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(huge); }, huge, "too large"));
}

TEST_F(Pcd, RejectsCompressedSizesThatCannotBeRight) {
  std::string bytes = xyzHeader("binary_compressed", "1000000");
  appendBytes<std::uint32_t>(bytes, 4);
  appendBytes<std::uint32_t>(bytes, 12000000);
  bytes += "abcd";
  const std::string path = writeFile("bomb.pcd", bytes);
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "corrupt binary_compressed data"));
}

TEST_F(Pcd, RejectsTruncatedBinaryBody) {
  const std::string source = pathOf("whole.pcd");
  io::writePointCloud(source, organizedCloudWithHoles(), io::Encoding::Binary);
  std::string bytes = readFile(source);
  // PCL pads binary files to a page boundary, so cut inside the 12 points x 24 bytes themselves.
  const std::size_t body = bytes.find("DATA binary\n") + std::string("DATA binary\n").size();
  bytes.resize(body + 12 * 24 - 7);
  const std::string path = writeFile("truncated.pcd", bytes);
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "header claims 12 points"));
}

TEST_F(Pcd, RejectsMissingCoordinateField) {
  const std::string path = writeFile("no_z.pcd",
                                     "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\n"
                                     "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "no 'z' field"));
}

TEST_F(Pcd, RejectsMismatchedHeaderCounts) {
  const std::string path = writeFile("sizes.pcd",
                                     "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                     "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "SIZE has 2 values for 3 FIELDS"));
}

TEST_F(Pcd, RejectsNanInUnorganizedCloud) {
  const std::string path = writeFile("nan.pcd", xyzHeader("ascii", "2") + "1 2 3\nnan nan nan\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "point 1 is not finite"));
}

// PCL itself would skip such lines with a warning and leave zero points behind.
TEST_F(Pcd, RejectsMalformedAsciiLines) {
  const std::string merged = writeFile("merged.pcd", xyzHeader("ascii", "3") + "1 2 3 4 5 6 7 8 9 10 11 12 13\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(merged); }, merged,
                        "line 10 (point 0): 13 values but the header declares 3 per point"));

  const std::string extra = writeFile("extra.pcd", xyzHeader("ascii", "3") + "1 2 3\n4 5 6 7\n7 8 9\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(extra); }, extra, "line 11 (point 1): 4 values"));

  const std::string word = writeFile("word.pcd", xyzHeader("ascii", "2") + "1 2 3\n4 five 6\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(word); }, word, "line 11 (point 1): 'five' is not a number"));

  const std::string few = writeFile("few.pcd", xyzHeader("ascii", "3") + "1.5 2.5 3.5\n\n4.5 5.5 6.5\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(few); }, few, "ends before point 2 of 3"));
}

// PCL's header parser would allocate for the first POINTS line before reading the second.
TEST_F(Pcd, RejectsRepeatedHeaderLines) {
  std::string header = xyzHeader("ascii", "1");
  header.insert(header.find("POINTS"), "POINTS 1000000000000\n");
  const std::string path = writeFile("twice.pcd", header + "1 2 3\n");
  EXPECT_TRUE(failsWith([&] { io::readPointCloud(path); }, path, "'POINTS' appears twice"));
}

TEST_F(Pcd, RefusesToWriteSingleRowOrganizedCloudWithHoles) {
  io::PointCloud cloud;
  cloud.points = {{1, 2, 3}, {NAN, NAN, NAN}};
  cloud.width = 2;
  cloud.height = 1;
  const std::string path = pathOf("row.pcd");
  EXPECT_TRUE(failsWith([&] { io::writePointCloud(path, cloud); }, path, "one-row organized cloud"));
}

}  // namespace
}  // namespace binpick::test
