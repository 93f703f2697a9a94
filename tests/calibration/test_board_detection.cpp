// Board detection on the virtual cell's rendered boards: corners where the truth says they are,
// partial boards, missing boards, 16-bit images, and the pose of the board.
#include "binpick/calibration/board_detection.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "binpick/io/image_file.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "thrown_message.hpp"

namespace binpick::calibration {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

struct RenderedView {
  simulation::BoardSpec spec;
  io::RigCalibration rig;
  Eigen::Isometry3d T_camera_board;
  cv::Mat white;
  std::vector<simulation::CornerObservation> truth;  // by corner id
};

// The white image of a render, kept in the build tree: each render is a whole pattern sequence
// and every test runs in its own process. Written through a rename, so parallel tests never read
// half a file.
cv::Mat cachedWhite(const std::string& name, const std::function<cv::Mat()>& render) {
  const std::filesystem::path path =
      std::filesystem::path(BINPICK_TEST_DATA_DIR) / ("board_detection_v1_" + name + ".png");
  cv::Mat white = io::readImageFile(path.string());
  if (!white.empty()) return white;
  white = render();
  std::filesystem::create_directories(path.parent_path());
  const std::string partial = path.string() + "." + std::to_string(::getpid()) + ".png";
  io::writeImageFile(partial, white);
  std::filesystem::rename(partial, path);
  return white;
}

simulation::CalibrationSequenceParams whiteImageParams(BoardType type) {
  simulation::CalibrationSequenceParams params;
  params.board.type = type;
  params.pattern_set.row_codes = false;  // only the white image is used here
  params.pattern_set.phase_steps = 0;
  params.poses.count = 1;
  params.poses.seed = 5;
  return params;
}

// One rendered view per board type.
const RenderedView& renderedView(BoardType type) {
  static std::map<BoardType, RenderedView> views;
  auto found = views.find(type);
  if (found != views.end()) return found->second;
  const simulation::CalibrationSequenceParams params = whiteImageParams(type);
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  RenderedView view{params.board, params.rig, {}, {}, {}};
  view.T_camera_board = simulation::randomBoardPoses(board, params.rig, params.poses).front();
  view.white = cachedWhite(boardTypeName(type), [&] {
    return simulation::renderCalibrationCapture(board, view.T_camera_board, params, 3).images.at(0);
  });
  view.truth = simulation::observeCorners(board, params.rig, view.T_camera_board);
  return views.emplace(type, view).first->second;
}

// The chessboard view's board moved sideways by `offset_x` camera metres, or so that its centre
// sits on the camera's left image edge (x = -0.40 z) when `offset_x` is NaN.
cv::Mat movedChessboard(const std::string& name, double offset_x) {
  const RenderedView& view = renderedView(BoardType::Chessboard);
  const simulation::CalibrationSequenceParams params = whiteImageParams(BoardType::Chessboard);
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  const Eigen::Vector2d face = board.printedFace().center();
  const Eigen::Vector3d centre = view.T_camera_board * Eigen::Vector3d(face.x(), face.y(), 0.0);
  Eigen::Isometry3d moved = view.T_camera_board;
  moved.translation().x() += std::isnan(offset_x) ? -0.40 * centre.z() - centre.x() : offset_x;
  return cachedWhite(name, [&] { return simulation::renderCalibrationWhiteImage(board, moved, params, 4); });
}

// Pixel error of each detected corner against the truth of the same id.
std::vector<double> cornerErrors(const BoardDetection& detection, const RenderedView& view) {
  std::vector<double> errors;
  for (std::size_t i = 0; i < detection.ids.size(); ++i) {
    errors.push_back((detection.pixels[i] - view.truth.at(detection.ids[i]).camera_pixel).norm());
  }
  return errors;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void expectCornersOnTruth(const BoardDetection& detection, const RenderedView& view) {
  const std::vector<double> errors = cornerErrors(detection, view);
  ASSERT_FALSE(errors.empty());
  EXPECT_LT(median(errors), 0.1);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.3);
}

TEST(BoardLayout, CornersAreTheVirtualBoardsCorners) {
  for (const BoardType type : {BoardType::Charuco, BoardType::Chessboard}) {
    simulation::BoardSpec spec;
    spec.type = type;
    const simulation::CalibrationBoard board(spec);
    const BoardLayout layout = spec.layout();
    ASSERT_EQ(layout.cornerCount(), static_cast<int>(board.corners().size()));
    for (const simulation::BoardCorner& corner : board.corners()) {
      EXPECT_LT((layout.cornerPoint(corner.id) - corner.point).norm(), 1e-12);
    }
  }
}

TEST(BoardLayout, BadLayoutsThrowNamingTheField) {
  BoardLayout layout;
  layout.squares_x = 2;
  EXPECT_TRUE(test::throwsNaming([&] { layout.validate(); }, "BoardLayout.squares_x"));
  layout = {};
  layout.marker_size = 0.04;
  EXPECT_TRUE(test::throwsNaming([&] { layout.validate(); }, "BoardLayout.marker_size"));
  layout = {};
  layout.dictionary = "DICT_9X9";
  EXPECT_TRUE(test::throwsNaming([&] { layout.validate(); }, "BoardLayout.dictionary"));
  EXPECT_TRUE(test::throwsNaming([&] { BoardLayout{}.cornerPoint(48); }, "corner id 48"));
  EXPECT_TRUE(test::throwsNaming([] { boardTypeFromName("circles"); }, "circles"));
}

TEST(BoardDetection, FindsEveryCharucoCornerOnTheTruth) {
  const RenderedView& view = renderedView(BoardType::Charuco);
  const BoardDetection detection = detectBoard(view.white, view.spec.layout());
  ASSERT_TRUE(detection.found()) << detection.problem;
  EXPECT_TRUE(detection.complete());
  EXPECT_TRUE(std::is_sorted(detection.ids.begin(), detection.ids.end()));
  expectCornersOnTruth(detection, view);
}

TEST(BoardDetection, FindsEveryChessboardCornerOnTheTruth) {
  const RenderedView& view = renderedView(BoardType::Chessboard);
  const BoardDetection detection = detectBoard(view.white, view.spec.layout());
  ASSERT_TRUE(detection.complete()) << detection.problem;
  // The view is close to upright, so corner 0 (top-left) is the truth's corner 0.
  expectCornersOnTruth(detection, view);
}

TEST(BoardDetection, ChessboardTurnedHalfATurnIsListedFromTheTopLeft) {
  const RenderedView& view = renderedView(BoardType::Chessboard);
  cv::Mat turned;
  cv::rotate(view.white, turned, cv::ROTATE_180);
  const BoardDetection detection = detectBoard(turned, view.spec.layout());
  ASSERT_TRUE(detection.complete()) << detection.problem;
  const Eigen::Vector2d first = detection.pixels.front(), last = detection.pixels.back();
  EXPECT_LT(first.sum(), last.sum());
}

TEST(BoardDetection, PartlyHiddenCharucoKeepsTheCornersSeen) {
  const RenderedView& view = renderedView(BoardType::Charuco);
  // Hide the board's left half, as if it hung out of the image.
  const double middle = view.truth.at(view.spec.layout().cornerCount() / 2).camera_pixel.x();
  cv::Mat cut = view.white.clone();
  cut.colRange(0, static_cast<int>(middle)).setTo(0);
  const BoardDetection detection = detectBoard(cut, view.spec.layout());
  ASSERT_TRUE(detection.found()) << detection.problem;
  EXPECT_FALSE(detection.complete());
  EXPECT_GT(detection.ids.size(), 6u);
  EXPECT_LT(detection.ids.size(), static_cast<std::size_t>(detection.expected));
  expectCornersOnTruth(detection, view);
}

TEST(BoardDetection, SmallSquaresStayOnTheTruth) {
  // The view at half the resolution: squares of about 25 pixels, markers 2 pixels from the
  // corners' white ring, where the largest refinement window would reach them.
  const RenderedView& view = renderedView(BoardType::Charuco);
  cv::Mat half;
  cv::resize(view.white, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  const BoardDetection detection = detectBoard(half, view.spec.layout());
  ASSERT_TRUE(detection.found()) << detection.problem;
  std::vector<double> errors;
  for (std::size_t i = 0; i < detection.ids.size(); ++i) {
    // Pixel centres at integers: a full-resolution pixel p lies at (p + 0.5) / 2 - 0.5.
    const Eigen::Vector2d truth =
        (view.truth.at(detection.ids[i]).camera_pixel + Eigen::Vector2d(0.5, 0.5)) / 2.0 - Eigen::Vector2d(0.5, 0.5);
    errors.push_back((detection.pixels[i] - truth).norm());
  }
  RecordProperty("max_corner_error_px", std::to_string(*std::max_element(errors.begin(), errors.end())));
  EXPECT_LT(median(errors), 0.1);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.3);
}

TEST(BoardDetection, NoBoardSaysWhy) {
  const cv::Mat grey(1024, 1280, CV_8UC1, cv::Scalar(90));
  BoardLayout layout;
  EXPECT_NE(detectBoard(grey, layout).problem.find("no ArUco marker"), std::string::npos);
  layout.type = BoardType::Chessboard;
  EXPECT_NE(detectBoard(grey, layout).problem.find("no chessboard in the image"), std::string::npos);
}

// Views without a complete chessboard are rejected, each with its reason, without the classic
// detector's exhaustive search (seconds per view); complete boards, blurred ones included, are
// still found.
TEST(BoardDetection, ChessboardViewWithoutABoardSaysSo) {
  const cv::Mat empty = movedChessboard("chessboard_empty", 2.0);  // the wall alone
  const BoardDetection detection = detectBoard(empty, renderedView(BoardType::Chessboard).spec.layout());
  EXPECT_FALSE(detection.found());
  EXPECT_NE(detection.problem.find("no chessboard in the image"), std::string::npos) << detection.problem;
}

TEST(BoardDetection, ChessboardCutByTheImageBorderSaysOnlyPartIsSeen) {
  const cv::Mat partial = movedChessboard("chessboard_partial_left", NAN);
  const BoardDetection detection = detectBoard(partial, renderedView(BoardType::Chessboard).spec.layout());
  EXPECT_FALSE(detection.found());
  EXPECT_NE(detection.problem.find("no complete 8x6 chessboard in the image, only part of one"), std::string::npos)
      << detection.problem;
}

TEST(BoardDetection, BlurredChessboardIsStillFound) {
  const RenderedView& view = renderedView(BoardType::Chessboard);
  cv::Mat blurred;
  cv::GaussianBlur(view.white, blurred, cv::Size(), 5.0);
  const BoardDetection detection = detectBoard(blurred, view.spec.layout());
  ASSERT_TRUE(detection.complete()) << detection.problem;
  const std::vector<double> errors = cornerErrors(detection, view);
  RecordProperty("median_corner_error_px", std::to_string(median(errors)));
  EXPECT_LT(median(errors), 0.5);  // found in the right order; blur costs accuracy (0.3 px)
}

TEST(BoardDetection, SixteenBitImagesGiveTheSameCorners) {
  const RenderedView& view = renderedView(BoardType::Charuco);
  cv::Mat wide;
  view.white.convertTo(wide, CV_16U, 257.0);
  const BoardDetection narrow_detection = detectBoard(view.white, view.spec.layout());
  const BoardDetection wide_detection = detectBoard(wide, view.spec.layout());
  ASSERT_EQ(wide_detection.ids, narrow_detection.ids);
  for (std::size_t i = 0; i < wide_detection.ids.size(); ++i) {
    EXPECT_LT((wide_detection.pixels[i] - narrow_detection.pixels[i]).norm(), 0.02);
  }
}

TEST(BoardDetection, UnusableImagesThrow) {
  EXPECT_TRUE(test::throwsNaming([] { detectBoard(cv::Mat(), BoardLayout{}); }, "image"));
  EXPECT_TRUE(
      test::throwsNaming([] { detectBoard(cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(0)), BoardLayout{}); }, "image"));
  BoardDetectionParams params;
  params.min_corners = 3;
  EXPECT_TRUE(
      test::throwsNaming([&] { detectBoard(cv::Mat(8, 8, CV_8UC1), {}, params); }, "BoardDetectionParams.min_corners"));
}

TEST(BoardPose, PoseOfTheDetectedBoardIsTheTruth) {
  for (const BoardType type : {BoardType::Charuco, BoardType::Chessboard}) {
    const RenderedView& view = renderedView(type);
    const BoardDetection detection = detectBoard(view.white, view.spec.layout());
    const auto pose = estimateBoardPose(detection, view.spec.layout(), view.rig.camera);
    ASSERT_TRUE(pose.has_value());
    EXPECT_LT(pose->rms_px, 0.2);
    const Eigen::AngleAxisd difference(pose->T_camera_board.linear().transpose() * view.T_camera_board.linear());
    EXPECT_LT(1e3 * (pose->T_camera_board.translation() - view.T_camera_board.translation()).norm(), 0.5);
    EXPECT_LT(std::abs(difference.angle()), 0.1 * kDegree);
  }
}

TEST(BoardPose, NoPoseWithoutABoard) {
  BoardDetection missing;
  missing.problem = "not there";
  EXPECT_FALSE(estimateBoardPose(missing, BoardLayout{}, simulation::makeVirtualRig().camera));
}

}  // namespace
}  // namespace binpick::calibration
