// Calibration sequences: OpenCV's own detectors find the rendered boards where the truth says the
// corners are, its pose estimation recovers the true board pose (which pins the board frame to
// OpenCV's), and a written sequence reads back.
#include "binpick/simulation/calibration_sequence.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::simulation {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Column codes only, no phase steps: 24 images instead of 52, to keep the tests fast.
CalibrationSequenceParams fastParams(BoardType type) {
  CalibrationSequenceParams params;
  params.board.type = type;
  params.pattern_set.row_codes = false;
  params.pattern_set.phase_steps = 0;
  params.poses.count = 2;
  return params;
}

// The same rig with a camera of a quarter of the resolution (and the same field of view): the
// same board poses fit, and a render takes a sixteenth of the time. For the tests that check
// files and seeds rather than image content.
CalibrationSequenceParams quarterResolution(CalibrationSequenceParams params) {
  io::LensIntrinsics& camera = params.rig.camera;
  camera.width /= 4;
  camera.height /= 4;
  camera.fx /= 4.0;
  camera.fy /= 4.0;
  camera.cx = (camera.cx + 0.5) / 4.0 - 0.5;  // pixel centres at integers
  camera.cy = (camera.cy + 0.5) / 4.0 - 0.5;
  return params;
}

// The most tilted of a few drawn poses: the hardest view for a detector. One pose per board type
// keeps the test fast (each render is a whole pattern sequence at full resolution).
Eigen::Isometry3d mostTiltedPose(const CalibrationBoard& board, const io::RigCalibration& rig) {
  BoardPoseParams params;
  params.count = 4;
  const std::vector<Eigen::Isometry3d> poses = randomBoardPoses(board, rig, params);
  return *std::max_element(poses.begin(), poses.end(), [](const auto& a, const auto& b) {
    return a.linear()(2, 2) > b.linear()(2, 2);  // the cosine of the tilt
  });
}

cv::Mat cameraMatrix(const io::LensIntrinsics& lens) {
  return (cv::Mat_<double>(3, 3) << lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0);
}

cv::Mat distortion(const io::LensIntrinsics& lens) {
  return cv::Mat(std::vector<double>(lens.distortion.begin(), lens.distortion.end()), true);
}

// The white image: the first of every pattern sequence.
cv::Mat whiteImage(const io::Capture& capture) {
  EXPECT_EQ(capture.metadata.patterns.at(0), "white");
  return capture.images.at(0);
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? NAN : values[values.size() / 2];
}

// Rotation angle between two poses and distance between their origins.
void expectSamePose(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth, double max_distance,
                    double max_angle) {
  const Eigen::AngleAxisd difference(estimate.linear().transpose() * truth.linear());
  const double distance = (estimate.translation() - truth.translation()).norm();
  ::testing::Test::RecordProperty("pose_error_mm", std::to_string(1e3 * distance));
  ::testing::Test::RecordProperty("pose_error_deg", std::to_string(std::abs(difference.angle()) / kDegree));
  EXPECT_LT(distance, max_distance);
  EXPECT_LT(std::abs(difference.angle()), max_angle);
}

Eigen::Isometry3d poseFrom(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat rotation;
  cv::Rodrigues(rvec, rotation);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.matrix()(r, c) = rotation.at<double>(r, c);
    T.matrix()(r, 3) = tvec.at<double>(r);
  }
  return T;
}

TEST(CalibrationSequence, OpenCvFindsTheCharucoCornersAndPoseOfTheTruth) {
  const CalibrationSequenceParams params = fastParams(BoardType::Charuco);
  const CalibrationBoard board(params.board, params.texel_size);
  const io::RigCalibration& rig = params.rig;
  const Eigen::Isometry3d T = mostTiltedPose(board, rig);
  const cv::Mat white = whiteImage(renderCalibrationCapture(board, T, params, 7));
  // OpenCV's own board definition, not the library's.
  const auto reference =
      cv::aruco::CharucoBoard::create(9, 7, 0.03f, 0.022f, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100));
  std::vector<std::vector<cv::Point2f>> markers;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(white, reference->dictionary, markers, marker_ids);
  EXPECT_EQ(marker_ids.size(), reference->ids.size());
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(markers, marker_ids, white, reference, corners, ids, cameraMatrix(rig.camera),
                                       distortion(rig.camera));
  ASSERT_EQ(ids.size(), board.corners().size());
  // interpolateCornersCharuco of OpenCV 4.5.4 to 4.x shifts its refined corners by +0.5 pixel
  // (opencv/opencv#25539): refining them again with cornerSubPix, which converges to the saddle
  // point whatever the start, gives the corners in OpenCV's (and this library's) convention of
  // pixel centres at integers.
  const std::vector<cv::Point2f> interpolated = corners;
  cv::cornerSubPix(white, corners, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  const std::vector<CornerObservation> truth = observeCorners(board, rig, T);
  std::vector<double> errors;
  Eigen::Vector2d interpolation_bias = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Eigen::Vector2d& true_pixel = truth.at(ids[i]).camera_pixel;
    errors.push_back((Eigen::Vector2d(corners[i].x, corners[i].y) - true_pixel).norm());
    interpolation_bias += Eigen::Vector2d(interpolated[i].x, interpolated[i].y) - true_pixel;
  }
  interpolation_bias /= static_cast<double>(ids.size());
  RecordProperty("interpolation_bias_px",
                 std::to_string(interpolation_bias.x()) + " " + std::to_string(interpolation_bias.y()));
  RecordProperty("median_corner_error_px", std::to_string(median(errors)));
  RecordProperty("max_corner_error_px", std::to_string(*std::max_element(errors.begin(), errors.end())));
  EXPECT_LT(median(errors), 0.1);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.3);

  // OpenCV's pose of its own board from these corners is the truth: the board frames agree.
  cv::Mat rvec, tvec;
  ASSERT_TRUE(cv::aruco::estimatePoseCharucoBoard(corners, ids, reference, cameraMatrix(rig.camera),
                                                  distortion(rig.camera), rvec, tvec));
  expectSamePose(poseFrom(rvec, tvec), T, 0.25e-3, 0.1 * kDegree);
}

TEST(CalibrationSequence, OpenCvFindsTheChessboardCornersAndPoseOfTheTruth) {
  const CalibrationSequenceParams params = fastParams(BoardType::Chessboard);
  const CalibrationBoard board(params.board, params.texel_size);
  const io::RigCalibration& rig = params.rig;
  const Eigen::Isometry3d T = mostTiltedPose(board, rig);
  const cv::Mat white = whiteImage(renderCalibrationCapture(board, T, params, 7));
  std::vector<cv::Point2f> corners;
  ASSERT_TRUE(cv::findChessboardCorners(white, cv::Size(8, 6), corners));
  cv::cornerSubPix(white, corners, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  // A 9 x 7 chessboard looks the same turned half a turn: the detector may list the corners
  // from either end. Match the order to the truth's ids before comparing.
  const std::vector<CornerObservation> truth = observeCorners(board, rig, T);
  ASSERT_EQ(corners.size(), truth.size());
  const auto error = [&](std::size_t i, std::size_t id) {
    return (Eigen::Vector2d(corners[i].x, corners[i].y) - truth[id].camera_pixel).norm();
  };
  if (error(0, 0) > error(0, truth.size() - 1)) std::reverse(corners.begin(), corners.end());
  std::vector<double> errors;
  for (std::size_t i = 0; i < corners.size(); ++i) errors.push_back(error(i, i));
  RecordProperty("median_corner_error_px", std::to_string(median(errors)));
  RecordProperty("max_corner_error_px", std::to_string(*std::max_element(errors.begin(), errors.end())));
  EXPECT_LT(median(errors), 0.1);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.3);

  // The usual chessboard object points, (column s, row s, 0) in detection order, give the truth.
  std::vector<cv::Point3f> object_points;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 8; ++col) object_points.emplace_back(col * 0.03f, row * 0.03f, 0.0f);
  }
  cv::Mat rvec, tvec;
  ASSERT_TRUE(cv::solvePnP(object_points, corners, cameraMatrix(rig.camera), distortion(rig.camera), rvec, tvec));
  expectSamePose(poseFrom(rvec, tvec), T, 0.25e-3, 0.1 * kDegree);
}

TEST(CalibrationSequence, SameSeedSameImagesAnotherSeedDiffers) {
  const CalibrationSequenceParams params = quarterResolution(fastParams(BoardType::Charuco));
  const CalibrationBoard board(params.board, params.texel_size);
  const Eigen::Isometry3d T = randomBoardPoses(board, params.rig, params.poses)[0];
  const io::Capture first = renderCalibrationCapture(board, T, params, 7);
  const io::Capture again = renderCalibrationCapture(board, T, params, 7);
  const io::Capture other = renderCalibrationCapture(board, T, params, 8);
  ASSERT_EQ(first.images.size(), reconstruction::patternNames(params.pattern_set).size());
  for (std::size_t i = 0; i < first.images.size(); i += 5) {
    EXPECT_EQ(cv::norm(first.images[i], again.images[i], cv::NORM_INF), 0.0);
    EXPECT_GT(cv::norm(first.images[i], other.images[i], cv::NORM_INF), 0.0);
  }
  // The exposure keeps the board's white below saturation.
  double peak = 0.0;
  cv::minMaxLoc(first.images[0], nullptr, &peak);
  EXPECT_LT(peak, 255.0);
  EXPECT_LE(first.metadata.exposure_us, params.exposure_us);
}

TEST(CalibrationSequence, TheWhiteImageAloneIsTheCapturesFirst) {
  for (const int bit_depth : {8, 16}) {
    CalibrationSequenceParams params = quarterResolution(fastParams(BoardType::Charuco));
    params.photometry.bit_depth = bit_depth;
    const CalibrationBoard board(params.board, params.texel_size);
    const Eigen::Isometry3d T = randomBoardPoses(board, params.rig, params.poses)[1];
    const cv::Mat white = renderCalibrationWhiteImage(board, T, params, 11);
    const cv::Mat first = whiteImage(renderCalibrationCapture(board, T, params, 11));
    ASSERT_EQ(white.type(), first.type());
    EXPECT_EQ(cv::norm(white, first, cv::NORM_INF), 0.0);
  }
}

class CalibrationSequenceFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = (fs::temp_directory_path() / ("binpick_calibration_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name()))
                     .string();
    fs::remove_all(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  std::string directory_;
};

TEST_F(CalibrationSequenceFiles, WrittenSequenceReadsBack) {
  CalibrationSequenceParams params = quarterResolution(fastParams(BoardType::Charuco));
  params.photometry.bit_depth = 16;
  const std::vector<Eigen::Isometry3d> poses = writeCalibrationSequence(directory_, params);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_FALSE(fs::exists(fs::path(directory_) / "pose_000" / "calib.yaml"));
  for (const char* pose : {"pose_000", "pose_001"}) {
    const io::Capture capture = io::readCapture((fs::path(directory_) / pose).string());
    EXPECT_EQ(capture.metadata.patterns, reconstruction::patternNames(params.pattern_set));
    EXPECT_EQ(capture.metadata.bit_depth, 16);
    EXPECT_EQ(capture.metadata.image_width, params.rig.camera.width);
    EXPECT_NE(capture.metadata.source.find("calibration sequence"), std::string::npos);
    EXPECT_GT(capture.metadata.exposure_us, 0.0);
  }
  const io::RigCalibration rig = io::readRigCalibration(directory_ + "/truth/rig.yaml");
  EXPECT_LT((rig.T_projector_camera.matrix() - params.rig.T_projector_camera.matrix()).norm(), 1e-12);
  EXPECT_EQ(rig.camera.fx, params.rig.camera.fx);

  const CalibrationTruth truth = readCalibrationTruth(directory_);
  EXPECT_EQ(truth.board.type, BoardType::Charuco);
  EXPECT_EQ(truth.board.dictionary, params.board.dictionary);
  EXPECT_EQ(truth.board.square_size, params.board.square_size);
  const CalibrationBoard board(params.board, params.texel_size);
  ASSERT_EQ(truth.corners.size(), board.corners().size());
  ASSERT_EQ(truth.poses.size(), 2u);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(truth.poses[i].capture, i == 0 ? "pose_000" : "pose_001");
    EXPECT_EQ(truth.poses[i].T_camera_board.matrix(), poses[i].matrix());
    const std::vector<CornerObservation> expected = observeCorners(board, params.rig, poses[i]);
    ASSERT_EQ(truth.poses[i].corners.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      EXPECT_EQ(truth.poses[i].corners[k].id, expected[k].id);
      EXPECT_EQ(truth.poses[i].corners[k].camera_pixel, expected[k].camera_pixel);
      EXPECT_EQ(truth.poses[i].corners[k].projector_pixel, expected[k].projector_pixel);
    }
  }
  // Never mixed with another sequence.
  EXPECT_THROW(writeCalibrationSequence(directory_, params), core::Error);
}

TEST(CalibrationSequence, BadParamsThrowNamingTheField) {
  const auto fails = [](auto change, const std::string& text) {
    CalibrationSequenceParams params;
    change(params);
    try {
      params.validate();
    } catch (const core::Error& e) {
      return std::string(e.what()).find(text) != std::string::npos ? ::testing::AssertionSuccess()
                                                                   : ::testing::AssertionFailure() << e.what();
    }
    return ::testing::AssertionFailure() << "did not throw";
  };
  using P = CalibrationSequenceParams;
  EXPECT_TRUE(fails([](P& p) { p.board.squares_x = 1; }, "CalibrationSequenceParams.board: BoardLayout.squares_x"));
  EXPECT_TRUE(fails([](P& p) { p.poses.count = -2; }, "CalibrationSequenceParams.poses: BoardPoseParams.count"));
  EXPECT_TRUE(fails([](P& p) { p.photometry.bit_depth = 12; },
                    "CalibrationSequenceParams.photometry: PhotometryParams.bit_depth"));
  EXPECT_TRUE(fails([](P& p) { p.pattern_set.projector_width = 1920; },
                    "CalibrationSequenceParams.pattern_set.projector_width"));
  EXPECT_TRUE(fails([](P& p) { p.pixel_samples = 0; }, "CalibrationSequenceParams.pixel_samples"));
  EXPECT_TRUE(fails([](P& p) { p.texel_size = -1.0; }, "CalibrationSequenceParams.texel_size"));
  EXPECT_TRUE(fails([](P& p) { p.background_distance = 1.0; }, "CalibrationSequenceParams.background_distance"));
  EXPECT_TRUE(fails([](P& p) { p.exposure_us = 0.0; }, "CalibrationSequenceParams.exposure_us"));
  EXPECT_TRUE(fails([](P& p) { p.max_white_counts = -1.0; }, "CalibrationSequenceParams.max_white_counts"));
}

}  // namespace
}  // namespace binpick::simulation
