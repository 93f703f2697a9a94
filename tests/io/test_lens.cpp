// LensIntrinsics: OpenCV's pinhole + k1 k2 p1 p2 k3 model, its inverse, and its validation.
#include "binpick/io/lens.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

// A 1280 x 1024 camera with distortion of the size a real industrial lens shows.
io::LensIntrinsics distortedLens() {
  io::LensIntrinsics lens;
  lens.width = 1280;
  lens.height = 1024;
  lens.fx = 1600.0;
  lens.fy = 1596.5;
  lens.cx = 641.3;
  lens.cy = 509.8;
  lens.distortion = {-0.08, 0.12, 4e-4, -3e-4, 0.0};
  return lens;
}

io::LensIntrinsics distortedLensWithK3() {
  io::LensIntrinsics lens = distortedLens();
  lens.distortion[4] = -0.05;
  return lens;
}

// Pixels on a grid covering the whole image, corners and edges included.
std::vector<Eigen::Vector2d> pixelGrid(const io::LensIntrinsics& lens) {
  std::vector<Eigen::Vector2d> pixels;
  for (int i = 0; i <= 16; ++i) {
    for (int j = 0; j <= 16; ++j) {
      pixels.emplace_back(-0.5 + i * lens.width / 16.0, -0.5 + j * lens.height / 16.0);
    }
  }
  return pixels;
}

cv::Matx33d cameraMatrix(const io::LensIntrinsics& lens) {
  return {lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0};
}

std::vector<double> distortionVector(const io::LensIntrinsics& lens) {
  return {lens.distortion.begin(), lens.distortion.end()};
}

::testing::AssertionResult failsNaming(const io::LensIntrinsics& lens, const std::string& fragment) {
  return binpick::test::throwsNaming([&] { lens.validate("camera"); }, fragment);
}

TEST(Lens, ProjectOfRayThroughPixelReturnsThePixel) {
  for (const io::LensIntrinsics& lens : {distortedLens(), distortedLensWithK3()}) {
    for (const Eigen::Vector2d& pixel : pixelGrid(lens)) {
      const Eigen::Vector3d ray = lens.rayThroughPixel(pixel);
      EXPECT_NEAR(ray.norm(), 1.0, 1e-12);
      EXPECT_GT(ray.z(), 0.0);
      const Eigen::Vector2d back = lens.project(2.7 * ray);
      EXPECT_LT((back - pixel).norm(), 1e-6) << "pixel " << pixel.transpose();
    }
  }
}

TEST(Lens, RayThroughProjectedPointPointsAtThePoint) {
  const io::LensIntrinsics lens = distortedLens();
  for (double x = -0.4; x <= 0.4; x += 0.1) {
    for (double y = -0.3; y <= 0.3; y += 0.1) {
      const Eigen::Vector3d point(x * 0.8, y * 0.8, 0.8);
      const Eigen::Vector3d ray = lens.rayThroughPixel(lens.project(point));
      EXPECT_LT((ray - point.normalized()).norm(), 1e-9) << point.transpose();
    }
  }
}

TEST(Lens, UndistortInvertsDistort) {
  const io::LensIntrinsics lens = distortedLensWithK3();
  for (double x = -0.42; x <= 0.42; x += 0.06) {
    for (double y = -0.34; y <= 0.34; y += 0.04) {
      const Eigen::Vector2d p(x, y);
      // 1e-10 in normalised coordinates is well below 1e-6 pixel at f = 1600.
      EXPECT_LT((lens.undistort(lens.distort(p)) - p).norm(), 1e-10) << p.transpose();
    }
  }
}

TEST(Lens, WithoutDistortionIsAPlainPinhole) {
  io::LensIntrinsics lens = distortedLens();
  lens.distortion = {};
  EXPECT_FALSE(lens.hasDistortion());
  EXPECT_TRUE(distortedLens().hasDistortion());
  // Pixel centres are at integer coordinates: the principal point looks straight ahead.
  const Eigen::Vector3d axis = lens.rayThroughPixel({lens.cx, lens.cy});
  EXPECT_LT((axis - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  const Eigen::Vector2d pixel = lens.project({0.1, -0.05, 0.5});
  EXPECT_NEAR(pixel.x(), lens.cx + lens.fx * 0.2, 1e-9);
  EXPECT_NEAR(pixel.y(), lens.cy - lens.fy * 0.1, 1e-9);
}

TEST(Lens, ProjectAgreesWithOpenCvProjectPoints) {
  for (const io::LensIntrinsics& lens : {distortedLens(), distortedLensWithK3()}) {
    std::vector<cv::Point3d> points;
    for (double x = -0.45; x <= 0.45; x += 0.05) {
      for (double y = -0.35; y <= 0.35; y += 0.05) points.emplace_back(x * 1.3, y * 1.3, 1.3);
    }
    std::vector<cv::Point2d> expected;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cameraMatrix(lens), distortionVector(lens),
                      expected);
    ASSERT_EQ(expected.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d pixel = lens.project({points[i].x, points[i].y, points[i].z});
      EXPECT_NEAR(pixel.x(), expected[i].x, 1e-6) << "point " << i;
      EXPECT_NEAR(pixel.y(), expected[i].y, 1e-6) << "point " << i;
    }
  }
}

TEST(Lens, UndistortAgreesWithOpenCvUndistortPoints) {
  const io::LensIntrinsics lens = distortedLens();
  const std::vector<Eigen::Vector2d> pixels = pixelGrid(lens);
  std::vector<cv::Point2d> distorted;
  for (const Eigen::Vector2d& p : pixels) distorted.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> expected;  // normalised, undistorted
  cv::undistortPoints(distorted, expected, cameraMatrix(lens), distortionVector(lens));
  ASSERT_EQ(expected.size(), pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector2d normalised((pixels[i].x() - lens.cx) / lens.fx, (pixels[i].y() - lens.cy) / lens.fy);
    const Eigen::Vector2d ours = lens.undistort(normalised);
    // Normalised coordinates. OpenCV stops after a few fixed-point iterations by default (ours
    // runs Newton to machine precision); for this mild lens both agree far below 1e-6 (~2e-3 px).
    EXPECT_NEAR(ours.x(), expected[i].x, 1e-6) << "pixel " << pixels[i].transpose();
    EXPECT_NEAR(ours.y(), expected[i].y, 1e-6) << "pixel " << pixels[i].transpose();
  }
}

TEST(Lens, UndistortMatchesOpenCvRunToConvergence) {
  const io::LensIntrinsics lens = distortedLensWithK3();
  const std::vector<Eigen::Vector2d> pixels = pixelGrid(lens);
  std::vector<cv::Point2d> distorted;
  for (const Eigen::Vector2d& p : pixels) distorted.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> expected;
  cv::undistortPoints(distorted, expected, cameraMatrix(lens), distortionVector(lens), cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT, 200, 0.0));
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d ray = lens.rayThroughPixel(pixels[i]);
    // Compared in pixels: the ray's normalised coordinates times the focal length.
    EXPECT_NEAR(ray.x() / ray.z() * lens.fx, expected[i].x * lens.fx, 1e-6);
    EXPECT_NEAR(ray.y() / ray.z() * lens.fy, expected[i].y * lens.fy, 1e-6);
  }
}

TEST(Lens, ValidateAcceptsARealisticLens) {
  EXPECT_NO_THROW(distortedLens().validate("camera"));
  EXPECT_NO_THROW(distortedLensWithK3().validate("projector"));
}

TEST(Lens, ValidateRejectsBadFieldsNamingThem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  io::LensIntrinsics lens = distortedLens();
  lens.fx = 0.0;
  EXPECT_TRUE(failsNaming(lens, "camera.fx must be positive"));
  lens = distortedLens();
  lens.fy = -1600.0;
  EXPECT_TRUE(failsNaming(lens, "camera.fy"));
  lens = distortedLens();
  lens.cx = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(failsNaming(lens, "camera.cx must be finite"));
  lens = distortedLens();
  lens.distortion[1] = nan;
  EXPECT_TRUE(failsNaming(lens, "camera.distortion must be finite"));
  lens = distortedLens();
  lens.width = 0;
  EXPECT_TRUE(failsNaming(lens, "camera.width"));
  lens = distortedLens();
  lens.height = -3;
  EXPECT_TRUE(failsNaming(lens, "camera.height"));
  lens = distortedLens();
  lens.fx = nan;
  EXPECT_TRUE(failsNaming(lens, "camera.fx"));
}

}  // namespace
}  // namespace binpick::test
