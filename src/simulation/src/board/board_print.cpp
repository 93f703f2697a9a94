// The print of a board: OpenCV's own ChArUco drawing, or a procedural chessboard.
#include "board_print.hpp"

#include <cmath>
#include <opencv2/aruco/charuco.hpp>

namespace binpick::simulation::detail {
namespace {

cv::Ptr<cv::aruco::CharucoBoard> charucoBoard(const BoardSpec& spec) {
  return cv::aruco::CharucoBoard::create(
      spec.squares_x, spec.squares_y, static_cast<float>(spec.square_size), static_cast<float>(spec.marker_size),
      cv::aruco::getPredefinedDictionary(calibration::arucoDictionaryId(spec.dictionary)));
}

cv::Mat drawChessboard(const BoardSpec& spec, int texels_per_square) {
  cv::Mat print(spec.squares_y * texels_per_square, spec.squares_x * texels_per_square, CV_8UC1, cv::Scalar(255));
  for (int row = 0; row < spec.squares_y; ++row) {
    for (int col = 0; col < spec.squares_x; ++col) {
      if ((row + col) % 2 != 0) continue;  // white
      print(cv::Rect(col * texels_per_square, row * texels_per_square, texels_per_square, texels_per_square)).setTo(0);
    }
  }
  return print;
}

}  // namespace

cv::Mat drawBoardPrint(const BoardSpec& spec, int texels_per_square) {
  spec.validate();
  if (spec.type == BoardType::Chessboard) return drawChessboard(spec, texels_per_square);
  // With no margin and an image of exactly squares_x by squares_y squares, OpenCV's drawing
  // puts square (col, row) on texels [col t, (col + 1) t) x [row t, (row + 1) t), in the frame
  // of its own object points (checked by the tests through OpenCV's pose estimation).
  cv::Mat print;
  charucoBoard(spec)->draw(cv::Size(spec.squares_x * texels_per_square, spec.squares_y * texels_per_square), print, 0,
                           1);
  return print;
}

std::vector<BoardCorner> boardCornerPoints(const BoardSpec& spec) {
  spec.validate();
  std::vector<BoardCorner> corners;
  if (spec.type == BoardType::Charuco) {
    const auto board = charucoBoard(spec);
    for (std::size_t i = 0; i < board->chessboardCorners.size(); ++i) {
      const cv::Point3f& p = board->chessboardCorners[i];
      // Back to double from OpenCV's floats through the square size, so that corners sit on the
      // grid exactly: p is (c + 1) s, (r + 1) s up to float rounding.
      const double c = std::round(p.x / spec.square_size), r = std::round(p.y / spec.square_size);
      corners.push_back({static_cast<int>(i), Eigen::Vector3d(c * spec.square_size, r * spec.square_size, 0.0)});
    }
    return corners;
  }
  for (int r = 0; r < spec.squares_y - 1; ++r) {
    for (int c = 0; c < spec.squares_x - 1; ++c) {
      corners.push_back(
          {static_cast<int>(corners.size()), Eigen::Vector3d(c * spec.square_size, r * spec.square_size, 0.0)});
    }
  }
  return corners;
}

Eigen::Vector2d squaresOrigin(const BoardSpec& spec) {
  if (spec.type == BoardType::Charuco) return Eigen::Vector2d::Zero();
  return Eigen::Vector2d::Constant(-spec.square_size);
}

}  // namespace binpick::simulation::detail
