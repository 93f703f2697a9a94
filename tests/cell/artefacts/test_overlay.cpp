// Where the overlay draws a part, in which colour, and which images it refuses.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "overlay.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

using cell::OverlayPart;
using cell::renderOverlay;

const cv::Vec3b kGreen(0, 255, 0), kYellow(0, 255, 255), kRed(0, 0, 255);

io::LensIntrinsics pinhole() {
  io::LensIntrinsics lens;
  lens.width = 640;
  lens.height = 480;
  lens.fx = lens.fy = 500.0;
  lens.cx = 320.0;
  lens.cy = 240.0;
  return lens;
}

OverlayPart partAt(const Eigen::Vector3d& position, int rank) {
  OverlayPart part;
  part.T_camera_model = Eigen::Translation3d(position) * Eigen::Isometry3d::Identity();
  part.pick_rank = rank;
  return part;
}

cv::Vec3b at(const cv::Mat& image, int x, int y) { return image.at<cv::Vec3b>(y, x); }

const cv::Mat kGrey(480, 640, CV_8UC1, cv::Scalar(90));
const std::vector<Eigen::Vector3f> kModel = {{0.f, 0.f, 0.f}, {0.04f, 0.f, 0.f}};

TEST(ArtefactsOverlay, DrawsTheModelOriginWhereTheCameraSeesItInItsRankColour) {
  // Origin at (0.02, 0.01, 0.5) m: pixel (320 + 500 * 0.04, 240 + 500 * 0.02) = (340, 250); the
  // second model point 4 cm further along x: (380, 250).
  const cv::Mat overlay = renderOverlay(kGrey, pinhole(), kModel, {partAt({0.02, 0.01, 0.5}, 0)});
  ASSERT_EQ(overlay.type(), CV_8UC3);
  EXPECT_EQ(at(overlay, 340, 250), kGreen);
  EXPECT_EQ(at(overlay, 380, 250), kGreen);
  EXPECT_EQ(at(overlay, 360, 250), cv::Vec3b(90, 90, 90));  // between the points: the image
  EXPECT_EQ(at(overlay, 10, 10), cv::Vec3b(90, 90, 90));
}

TEST(ArtefactsOverlay, ColoursPicksGreenToYellowAndTheRestRed) {
  const cv::Mat overlay =
      renderOverlay(kGrey, pinhole(), kModel,
                    {partAt({0.0, 0.0, 0.5}, 2), partAt({-0.2, 0.0, 0.5}, 0), partAt({0.0, -0.2, 0.5}, -1)});
  EXPECT_EQ(at(overlay, 320, 240), kYellow);  // the last pick
  EXPECT_EQ(at(overlay, 120, 240), kGreen);   // the first
  EXPECT_EQ(at(overlay, 320, 40), kRed);      // not picked
}

TEST(ArtefactsOverlay, IncludesTheLensDistortion) {
  io::LensIntrinsics lens = pinhole();
  lens.distortion = {-0.2, 0.05, 0.001, -0.001, 0.0};
  const Eigen::Vector3d origin(0.2, 0.15, 0.5);
  const Eigen::Vector2d expected = lens.project(origin);
  ASSERT_GT((expected - pinhole().project(origin)).norm(), 5.0);  // distortion matters here
  const cv::Mat overlay = renderOverlay(kGrey, lens, {{0.f, 0.f, 0.f}}, {partAt(origin, 0)});
  EXPECT_EQ(at(overlay, cvRound(expected.x()), cvRound(expected.y())), kGreen);
}

TEST(ArtefactsOverlay, SkipsPointsBehindTheCameraOrOutsideTheImage) {
  const std::vector<OverlayPart> parts = {partAt({0.0, 0.0, -0.5}, 0), partAt({2.0, 0.0, 0.5}, 1)};
  const cv::Mat overlay = renderOverlay(kGrey, pinhole(), kModel, parts);
  cv::Mat expected;
  cv::cvtColor(kGrey, expected, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(cv::norm(overlay, expected, cv::NORM_INF), 0.0);
}

TEST(ArtefactsOverlay, DrawsTheGraspTripodXRedYGreen) {
  OverlayPart part = partAt({0.5, 0.3, 2.0}, -1);  // its origin marker well away from the grasp
  part.T_camera_grasp = Eigen::Translation3d(0.0, 0.0, 0.5) * Eigen::Isometry3d::Identity();
  // The tripod's axes are kOverlayTripodLength (2 cm) long: x ends at pixel (340, 240), y at
  // (320, 260). Their midpoints:
  const cv::Mat overlay = renderOverlay(kGrey, pinhole(), {}, {part});
  EXPECT_EQ(at(overlay, 332, 240), kRed);
  EXPECT_EQ(at(overlay, 320, 252), kGreen);
}

TEST(ArtefactsOverlay, ScalesSixteenBitImagesToEightBit) {
  const cv::Mat grey16(480, 640, CV_16UC1, cv::Scalar(257 * 100));
  const cv::Mat overlay = renderOverlay(grey16, pinhole(), kModel, {});
  ASSERT_EQ(overlay.type(), CV_8UC3);
  EXPECT_EQ(at(overlay, 5, 5), cv::Vec3b(100, 100, 100));
}

TEST(ArtefactsOverlay, RefusesImagesItCannotDrawOn) {
  const io::LensIntrinsics lens = pinhole();
  EXPECT_TRUE(throwsNaming([&] { renderOverlay(cv::Mat(), lens, kModel, {}); }, "empty"));
  EXPECT_TRUE(throwsNaming([&] { renderOverlay(cv::Mat(480, 640, CV_8UC3), lens, kModel, {}); }, "grey"));
  EXPECT_TRUE(throwsNaming([&] { renderOverlay(cv::Mat(480, 640, CV_32FC1), lens, kModel, {}); }, "grey"));
  EXPECT_TRUE(throwsNaming([&] { renderOverlay(cv::Mat(240, 320, CV_8UC1), lens, kModel, {}); }, "320x240"));
}

}  // namespace
}  // namespace binpick::test
