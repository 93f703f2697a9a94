// Projector corners from local homographies (Moreno & Taubin) against the virtual cell's truth:
// every corner's projector pixel where the renderer says the projector sees it.
#include "binpick/calibration/projector_corners.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "binpick/calibration/rig_views.hpp"
#include "binpick/io/capture.hpp"
#include "rig_test_data.hpp"
#include "thrown_message.hpp"

namespace binpick::calibration {
namespace {

using test::rigTestData;

std::map<int, Eigen::Vector2d> trueProjectorPixels(const simulation::CalibrationTruthPose& pose) {
  std::map<int, Eigen::Vector2d> pixels;
  for (const simulation::CornerObservation& corner : pose.corners) pixels[corner.id] = corner.projector_pixel;
  return pixels;
}

double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
}

// Projector-pixel errors of the corners found in one view.
std::vector<double> errorsAgainstTruth(const ProjectorCorners& found, const simulation::CalibrationTruthPose& pose) {
  const std::map<int, Eigen::Vector2d> truth = trueProjectorPixels(pose);
  std::vector<double> errors;
  for (const ProjectorCorner& corner : found.corners) {
    errors.push_back((corner.projector - truth.at(corner.id)).norm());
  }
  return errors;
}

// The board's corners in the camera image, and the same corners at their true pixels.
struct Corners {
  BoardDetection detected;
  BoardDetection exact;
};

Corners cornersOf(const io::Capture& capture, const simulation::CalibrationTruthPose& pose) {
  Corners corners;
  corners.detected = detectBoard(capture.images[0], rigTestData().layout);
  corners.exact = corners.detected;
  std::map<int, Eigen::Vector2d> truth;
  for (const simulation::CornerObservation& corner : pose.corners) truth[corner.id] = corner.camera_pixel;
  for (std::size_t i = 0; i < corners.exact.ids.size(); ++i) {
    corners.exact.pixels[i] = truth.at(corners.exact.ids[i]);
  }
  return corners;
}

void recordQuantiles(const std::string& name, const std::vector<double>& errors) {
  ::testing::Test::RecordProperty(name + "_median_px", std::to_string(quantile(errors, 0.5)));
  ::testing::Test::RecordProperty(name + "_p95_px", std::to_string(quantile(errors, 0.95)));
  ::testing::Test::RecordProperty(name + "_max_px", std::to_string(quantile(errors, 1.0)));
}

// Two measurements per corner: the fit alone (the homography evaluated at the true camera
// pixel), and end to end from the detected camera corner, whose error the homography carries
// into the projector image magnified by the projector's pixels per camera pixel (about 2 here).
TEST(ProjectorCorners, EveryCornerOfEveryViewLandsOnTheTruth) {
  const test::RigTestData& data = rigTestData();
  const simulation::CalibrationTruth truth = simulation::readCalibrationTruth(data.sequence);
  std::vector<double> fit_errors, errors;
  for (std::size_t v = 0; v < data.views.size(); ++v) {
    SCOPED_TRACE(data.views[v]);
    const io::Capture capture = io::readCapture(data.views[v]);
    const Corners corners = cornersOf(capture, truth.poses[v]);
    ASSERT_TRUE(corners.detected.found()) << corners.detected.problem;
    const reconstruction::DecodedCapture decoded = reconstruction::decodeCapture(capture);
    const ProjectorCorners exact = findProjectorCorners(decoded, corners.exact);
    const ProjectorCorners found = findProjectorCorners(decoded, corners.detected);
    // The whole board is inside both images in every pose: nothing may be lost.
    EXPECT_EQ(found.corners.size(), corners.detected.ids.size());
    EXPECT_EQ(exact.corners.size(), corners.detected.ids.size());
    for (const double e : errorsAgainstTruth(exact, truth.poses[v])) fit_errors.push_back(e);
    for (const double e : errorsAgainstTruth(found, truth.poses[v])) errors.push_back(e);
  }
  ASSERT_GT(errors.size(), 400u);
  recordQuantiles("fit", fit_errors);
  recordQuantiles("end_to_end", errors);
  // Gray codes alone quantise each decoded pixel to half a projector pixel; the fit over
  // thousands of pixels per corner averages that out.
  EXPECT_LT(quantile(fit_errors, 0.5), 0.05);
  EXPECT_LT(quantile(fit_errors, 1.0), 0.25);
  EXPECT_LT(quantile(errors, 0.5), 0.25);
  EXPECT_LT(quantile(errors, 1.0), 0.8);
}

// Where the board leaves the projector's light the decoded pixels stop: corners whose window is
// cut there must be dropped, never extrapolated, and the others must stay exact.
TEST(ProjectorCorners, CornersAtTheEdgeOfTheDecodedAreaAreDroppedNotExtrapolated) {
  const test::RigTestData& data = rigTestData();
  const io::Capture capture = io::readCapture(data.views[0]);
  const BoardDetection board = detectBoard(capture.images[0], data.layout);
  ASSERT_TRUE(board.complete()) << board.problem;
  reconstruction::DecodedCapture decoded = reconstruction::decodeCapture(capture);
  // Cut through the middle column of corners.
  std::vector<double> xs;
  for (const Eigen::Vector2d& pixel : board.pixels) xs.push_back(pixel.x());
  const double cut = quantile(xs, 0.5);
  decoded.column = decoded.column.clone();
  decoded.row = decoded.row.clone();
  decoded.column.colRange(static_cast<int>(std::ceil(cut)), decoded.width).setTo(NAN);

  const ProjectorCornerParams params;
  const ProjectorCorners found = findProjectorCorners(decoded, board, params);
  ASSERT_GE(found.corners.size(), 12u);
  for (const ProjectorCorner& corner : found.corners) {
    EXPECT_LT(corner.camera.x(), cut - params.min_hull_depth) << "corner " << corner.id << " was extrapolated";
  }
  EXPECT_GT(found.outside_data + found.too_few_decoded, 0);
  EXPECT_EQ(static_cast<std::size_t>(found.dropped()) + found.corners.size(), board.ids.size());
  const simulation::CalibrationTruth truth = simulation::readCalibrationTruth(data.sequence);
  EXPECT_LT(quantile(errorsAgainstTruth(found, truth.poses[0]), 1.0), 0.8);
}

TEST(ProjectorCorners, ACaptureWithoutRowsIsRefused) {
  const io::Capture capture = io::readCapture(rigTestData().no_rows);
  const reconstruction::DecodedCapture decoded = reconstruction::decodeCapture(capture);
  const BoardDetection board = detectBoard(capture.images[0], rigTestData().layout);
  ASSERT_TRUE(board.found());
  EXPECT_TRUE(test::throwsNaming([&] { findProjectorCorners(decoded, board); }, "row codes"));
}

TEST(ProjectorCorners, BadParamsAreNamed) {
  const reconstruction::DecodedCapture empty;
  const BoardDetection none;
  const auto fails = [&](auto change, const std::string& text) {
    ProjectorCornerParams params;
    change(params);
    return test::throwsNaming([&] { findProjectorCorners(empty, none, params); }, text);
  };
  using P = ProjectorCornerParams;
  EXPECT_TRUE(fails([](P& p) { p.half_window = 1; }, "ProjectorCornerParams.half_window"));
  EXPECT_TRUE(fails([](P& p) { p.min_decoded_pixels = 3; }, "ProjectorCornerParams.min_decoded_pixels"));
  EXPECT_TRUE(fails([](P& p) { p.ransac_threshold = 0.0; }, "ProjectorCornerParams.ransac_threshold"));
  EXPECT_TRUE(fails([](P& p) { p.min_inlier_share = 1.5; }, "ProjectorCornerParams.min_inlier_share"));
  EXPECT_TRUE(fails([](P& p) { p.min_hull_depth = NAN; }, "ProjectorCornerParams.min_hull_depth"));
}

}  // namespace
}  // namespace binpick::calibration
