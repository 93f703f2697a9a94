// CalibrationBoard and randomBoardPoses: the board's geometry and corners against OpenCV's own
// board definitions, its print, the pose draws, and spec validation. Nothing is rendered here
// (test_calibration_sequence.cpp renders and detects).
#include "binpick/simulation/calibration_board.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <opencv2/aruco/charuco.hpp>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/virtual_rig.hpp"
#include "mesh_test_utils.hpp"
#include "thrown_message.hpp"

namespace binpick::simulation {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

BoardSpec chessboardSpec() {
  BoardSpec spec;
  spec.type = BoardType::Chessboard;
  return spec;
}

using binpick::test::throwsNaming;

TEST(CalibrationBoard, CharucoCornersAreOpenCvsInOpenCvsOrder) {
  const BoardSpec spec;  // 9 x 7 ChArUco
  const CalibrationBoard board(spec);
  const auto reference = cv::aruco::CharucoBoard::create(
      spec.squares_x, spec.squares_y, static_cast<float>(spec.square_size), static_cast<float>(spec.marker_size),
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100));
  ASSERT_EQ(board.corners().size(), reference->chessboardCorners.size());
  for (std::size_t i = 0; i < board.corners().size(); ++i) {
    const cv::Point3f& p = reference->chessboardCorners[i];
    EXPECT_EQ(board.corners()[i].id, static_cast<int>(i));
    EXPECT_NEAR((board.corners()[i].point - Eigen::Vector3d(p.x, p.y, p.z)).norm(), 0.0, 1e-6);
  }
}

TEST(CalibrationBoard, ChessboardCornersAreRowMajorFromTheFirstInnerCorner) {
  const BoardSpec spec = chessboardSpec();
  const CalibrationBoard board(spec);
  ASSERT_EQ(board.corners().size(), static_cast<std::size_t>(8 * 6));
  EXPECT_NEAR(board.corners()[0].point.norm(), 0.0, 1e-12);
  EXPECT_NEAR((board.corners()[1].point - Eigen::Vector3d(0.03, 0.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((board.corners()[8].point - Eigen::Vector3d(0.0, 0.03, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((board.corners().back().point - Eigen::Vector3d(0.21, 0.15, 0.0)).norm(), 0.0, 1e-12);
}

TEST(CalibrationBoard, MeshIsAClosedBoxBehindThePrint) {
  for (const BoardSpec& spec : {BoardSpec(), chessboardSpec()}) {
    const CalibrationBoard board(spec);
    const io::TriangleMesh& mesh = board.mesh();
    EXPECT_EQ(test::closedManifoldProblem(mesh), "");
    const Eigen::Vector2d size = board.printedFace().sizes();
    EXPECT_NEAR(size.x(), 9 * 0.03 + 2 * spec.margin, 1e-9);
    EXPECT_NEAR(size.y(), 7 * 0.03 + 2 * spec.margin, 1e-9);
    EXPECT_NEAR(test::signedVolume(mesh), size.x() * size.y() * spec.thickness, 1e-9);
    // The triangles at z = 0 form the print; their outward normal is -z.
    int print_triangles = 0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      if (std::max({std::abs(a.z()), std::abs(b.z()), std::abs(c.z())}) > 0.0) continue;
      ++print_triangles;
      EXPECT_LT((b - a).cross(c - a).z(), 0.0);
    }
    EXPECT_EQ(print_triangles, 2);
  }
}

TEST(CalibrationBoard, PrintHasABlackTopLeftSquareAndAWhiteMargin) {
  for (const BoardSpec& spec : {BoardSpec(), chessboardSpec()}) {
    const CalibrationBoard board(spec);
    const Eigen::Vector2d top_left = board.printedFace().min() + Eigen::Vector2d::Constant(spec.margin);
    const double s = spec.square_size;
    const auto at = [&](double col, double row) { return board.albedo(top_left + Eigen::Vector2d(col * s, row * s)); };
    EXPECT_NEAR(at(0.5, 0.5), spec.black_albedo, 1e-6) << boardTypeName(spec.type);
    EXPECT_NEAR(at(1.5, 1.5), spec.black_albedo, 1e-6);
    EXPECT_NEAR(at(8.5, 6.5), spec.black_albedo, 1e-6);
    // White squares (a ChArUco marker's white... is inside; its quiet zone is white).
    EXPECT_NEAR(at(1.04, 0.5), spec.white_albedo, 1e-6);
    EXPECT_NEAR(at(0.5, 1.04), spec.white_albedo, 1e-6);
    EXPECT_NEAR(board.albedo(board.printedFace().min() + Eigen::Vector2d(0.005, 0.1)), spec.white_albedo, 1e-6);
    // An edge between squares is half way grey, and a pixel-sized average straddling it too.
    EXPECT_NEAR(at(1.0, 0.5), 0.5 * (spec.white_albedo + spec.black_albedo), 1e-3);
    EXPECT_NEAR(board.meanAlbedo(top_left + Eigen::Vector2d(s, 0.5 * s), Eigen::Matrix2d::Identity() * 5e-4, 4),
                0.5 * (spec.white_albedo + spec.black_albedo), 1e-3);
  }
}

TEST(CalibrationBoard, CharucoMarkersAreInTheWhiteSquares) {
  const BoardSpec spec;
  const CalibrationBoard board(spec);
  // Square (1, 0) holds marker 0: a black border bit just inside the marker's outline.
  const double inset = 0.5 * (spec.square_size - spec.marker_size);
  const Eigen::Vector2d marker_corner(spec.square_size + inset, inset);
  const double bit = spec.marker_size / 7.0;  // 5 x 5 bits plus the border
  EXPECT_NEAR(board.albedo(marker_corner + Eigen::Vector2d(0.5 * bit, 0.5 * bit)), spec.black_albedo, 1e-6);
  EXPECT_NEAR(board.albedo(marker_corner - Eigen::Vector2d(0.5 * inset, 0.5 * inset)), spec.white_albedo, 1e-6);
}

// Every marker's bits, read off the print at the cells of OpenCV's own marker object points,
// are the dictionary's code for its id: the print, the object points and the marker ids agree,
// orientation included, for an odd and an even number of rows.
TEST(CalibrationBoard, CharucoMarkersAreOpenCvsAtOpenCvsObjectPoints) {
  for (const int rows : {7, 6}) {
    BoardSpec spec;
    spec.squares_y = rows;
    const CalibrationBoard board(spec);
    const auto dictionary = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100);
    const auto reference = cv::aruco::CharucoBoard::create(spec.squares_x, rows, static_cast<float>(spec.square_size),
                                                           static_cast<float>(spec.marker_size), dictionary);
    const int n = dictionary->markerSize;
    int wrong_cells = 0;
    for (std::size_t m = 0; m < reference->ids.size(); ++m) {
      const int id = reference->ids[m];
      const cv::Mat bits = cv::aruco::Dictionary::getBitsFromByteList(dictionary->bytesList.rowRange(id, id + 1), n);
      // Corners clockwise from the top-left: 0, 1 along the marker's x, 3 along its y.
      const auto& c = reference->objPoints[m];
      const Eigen::Vector2d origin(c[0].x, c[0].y), across(c[1].x - c[0].x, c[1].y - c[0].y),
          down(c[3].x - c[0].x, c[3].y - c[0].y);
      for (int i = -1; i <= n; ++i) {  // the black border too
        for (int j = -1; j <= n; ++j) {
          const bool white = i >= 0 && j >= 0 && i < n && j < n && bits.at<uint8_t>(i, j) != 0;
          const Eigen::Vector2d cell = origin + (j + 1.5) / (n + 2) * across + (i + 1.5) / (n + 2) * down;
          const double expected = white ? spec.white_albedo : spec.black_albedo;
          if (std::abs(board.albedo(cell) - expected) > 0.05) ++wrong_cells;
        }
      }
    }
    EXPECT_EQ(wrong_cells, 0) << rows << " rows";
  }
}

TEST(CalibrationBoard, BadSpecsThrowNamingTheField) {
  const auto build = [](auto change) {
    return [change] {
      BoardSpec spec;
      change(spec);
      CalibrationBoard board(spec);
    };
  };
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.squares_x = 2; }), "BoardLayout.squares_x"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.squares_y = 0; }), "BoardLayout.squares_y"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.square_size = -0.01; }), "BoardLayout.square_size"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.marker_size = 0.03; }), "BoardLayout.marker_size"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.dictionary = "DICT_9X9_1"; }), "BoardLayout.dictionary"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) {
                             s.dictionary = "DICT_4X4_50";
                             s.squares_x = s.squares_y = 12;  // 72 markers
                           }),
                           "BoardLayout.dictionary DICT_4X4_50 holds 50 markers"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.margin = NAN; }), "BoardSpec.margin"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.thickness = 0.0; }), "BoardSpec.thickness"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.white_albedo = 1.5; }), "BoardSpec.white_albedo"));
  EXPECT_TRUE(throwsNaming(build([](BoardSpec& s) { s.black_albedo = 0.9; }), "BoardSpec.black_albedo"));
  EXPECT_TRUE(throwsNaming([] { CalibrationBoard board(BoardSpec(), 0.0); }, "texel_size"));
  EXPECT_TRUE(throwsNaming([] { boardTypeFromName("circles"); }, "circles"));
  // A chessboard needs neither markers nor a dictionary.
  BoardSpec chessboard = chessboardSpec();
  chessboard.marker_size = 1.0;
  chessboard.dictionary = "none";
  EXPECT_NO_THROW(CalibrationBoard{chessboard});
}

TEST(BoardPoses, BadParamsThrowNamingTheField) {
  const CalibrationBoard board{BoardSpec()};
  const io::RigCalibration rig = makeVirtualRig();
  const auto draw = [&](auto change) {
    return [&board, &rig, change] {
      BoardPoseParams params;
      change(params);
      randomBoardPoses(board, rig, params);
    };
  };
  EXPECT_TRUE(throwsNaming(draw([](BoardPoseParams& p) { p.count = -1; }), "BoardPoseParams.count"));
  EXPECT_TRUE(throwsNaming(draw([](BoardPoseParams& p) { p.max_distance = 0.5; }), "BoardPoseParams.max_distance"));
  EXPECT_TRUE(throwsNaming(draw([](BoardPoseParams& p) { p.max_tilt = 2.0; }), "BoardPoseParams.max_tilt"));
  EXPECT_TRUE(
      throwsNaming(draw([](BoardPoseParams& p) { p.min_facing_cosine = 1.0; }), "BoardPoseParams.min_facing_cosine"));
  EXPECT_TRUE(throwsNaming(draw([](BoardPoseParams& p) { p.max_attempts = 0; }), "BoardPoseParams.max_attempts"));
  // A board larger than the projector's field at any allowed distance cannot be placed.
  BoardSpec huge;
  huge.squares_x = 15;
  huge.square_size = 0.06;
  BoardPoseParams params;
  params.max_attempts = 50;
  EXPECT_TRUE(
      throwsNaming([&] { randomBoardPoses(CalibrationBoard(huge), rig, params); }, "no board pose in 50 draws"));
}

// The corners of the printed face's outline and its centre, projected independently of the
// library's own check.
bool outlineInside(const io::LensIntrinsics& lens, const Eigen::Isometry3d& T_device_board,
                   const Eigen::AlignedBox2d& face) {
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d c = face.corner(static_cast<Eigen::AlignedBox2d::CornerType>(k));
    const Eigen::Vector3d p = T_device_board * Eigen::Vector3d(c.x(), c.y(), 0.0);
    if (p.z() <= 0.0) return false;
    const Eigen::Vector2d pixel = lens.project(p);
    if (pixel.x() < 0.0 || pixel.y() < 0.0 || pixel.x() > lens.width - 1 || pixel.y() > lens.height - 1) {
      return false;
    }
  }
  return true;
}

TEST(BoardPoses, EveryPoseKeepsTheWholeBoardInBothImagesFacingBoth) {
  const io::RigCalibration rig = makeVirtualRig();
  for (const BoardSpec& spec : {BoardSpec(), chessboardSpec()}) {
    const CalibrationBoard board(spec);
    BoardPoseParams params;
    params.count = 40;
    const std::vector<Eigen::Isometry3d> poses = randomBoardPoses(board, rig, params);
    ASSERT_EQ(poses.size(), 40u);
    double min_z = 1e9, max_z = 0.0, max_tilt = 0.0;
    Eigen::Vector2d tilt_direction_sum = Eigen::Vector2d::Zero();
    for (const Eigen::Isometry3d& T : poses) {
      EXPECT_TRUE(outlineInside(rig.camera, T, board.printedFace()));
      EXPECT_TRUE(outlineInside(rig.projector, rig.T_projector_camera * T, board.printedFace()));
      EXPECT_EQ(observeCorners(board, rig, T).size(), board.corners().size());
      const Eigen::Vector3d normal = -T.linear().col(2);  // the print's outward normal
      const Eigen::Vector3d centre =
          T * Eigen::Vector3d(board.printedFace().center().x(), board.printedFace().center().y(), 0.0);
      EXPECT_GT(normal.dot(-centre.normalized()), 0.3);
      const Eigen::Vector3d projector = rig.T_projector_camera.inverse().translation();
      EXPECT_GT(normal.dot((projector - centre).normalized()), 0.3);
      min_z = std::min(min_z, centre.z());
      max_z = std::max(max_z, centre.z());
      max_tilt = std::max(max_tilt, std::acos(-normal.z()));
      tilt_direction_sum += normal.head<2>().normalized();
    }
    // The poses spread over the working volume and tilt in varying directions.
    EXPECT_GE(min_z, 0.7 - 1e-9);
    EXPECT_LE(max_z, 1.05 + 1e-9);
    EXPECT_GT(max_z - min_z, 0.2);
    EXPECT_GT(max_tilt, 30.0 * kDegree);
    EXPECT_LE(max_tilt, params.max_tilt + 1e-9);
    EXPECT_LT(tilt_direction_sum.norm(), 0.5 * poses.size());
  }
}

TEST(BoardPoses, SameSeedSamePosesAnotherSeedDiffers) {
  const CalibrationBoard board{BoardSpec()};
  const io::RigCalibration rig = makeVirtualRig();
  BoardPoseParams params;
  params.count = 6;
  const auto first = randomBoardPoses(board, rig, params);
  const auto again = randomBoardPoses(board, rig, params);
  params.count = 3;
  const auto fewer = randomBoardPoses(board, rig, params);
  params.count = 6;
  params.seed = 2;
  const auto other = randomBoardPoses(board, rig, params);
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].matrix(), again[i].matrix());
    if (i < fewer.size()) {
      EXPECT_EQ(first[i].matrix(), fewer[i].matrix());
    }
    EXPECT_GT((first[i].translation() - other[i].translation()).norm(), 1e-3);
  }
}

TEST(BoardPoses, ObservedCornersAreTheProjectedTruth) {
  const CalibrationBoard board{BoardSpec()};
  const io::RigCalibration rig = makeVirtualRig();
  BoardPoseParams params;
  params.count = 1;
  const Eigen::Isometry3d T = randomBoardPoses(board, rig, params)[0];
  for (const CornerObservation& o : observeCorners(board, rig, T)) {
    const Eigen::Vector3d p = T * board.corners()[o.id].point;
    EXPECT_NEAR((o.camera_pixel - rig.camera.project(p)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((o.projector_pixel - rig.projector.project(rig.T_projector_camera * p)).norm(), 0.0, 1e-9);
  }
  // Turned away from the rig, the board shows no corner.
  Eigen::Isometry3d away = T;
  away.linear() = T.linear() * Eigen::AngleAxisd(3.14159265358979, Eigen::Vector3d::UnitY());
  EXPECT_TRUE(observeCorners(board, rig, away).empty());
}

}  // namespace
}  // namespace binpick::simulation
