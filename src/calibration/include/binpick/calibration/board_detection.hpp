#pragma once
// Finding the board's corners in a camera image, to sub-pixel precision, and the board's pose.
//
// ChArUco: ArUco markers, then the corners between them (cv::aruco::interpolateCornersCharuco),
// refined again with cv::cornerSubPix (OpenCV 4.6's interpolation leaves them half a pixel off,
// opencv/opencv#25539). A board partly out of the image or partly covered still yields the
// corners that are seen, each with its id. Chessboard: cv::findChessboardCorners finds all
// corners or none; a 180-degree turned chessboard looks the same, so the order is made to run
// from the corner nearest the image's top-left (boards must then stay within +-90 degrees of
// upright across views; ChArUco has no such ambiguity).
// Pixel centres at integer coordinates. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/io/lens.hpp"

namespace binpick::calibration {

struct BoardDetectionParams {
  // Largest cornerSubPix search window half-size, pixels. Smaller squares get a smaller window,
  // one that stays clear of the ChArUco markers (chessboard: inside the squares), at least 2.
  int subpixel_half_window = 5;
  // A chessboard's window: this share of its smallest squares' side in the image, at most
  // chessboard_half_window pixels (a blurred corner needs a window as wide as the blur).
  double chessboard_window_share = 0.3;
  int chessboard_half_window = 15;
  // A chessboard's corners are refined on the image divided by its local white level, which
  // keeps the light's slope across the board from moving blurred corners.
  bool flatten_chessboard = true;
  // A view with fewer corners is "not found". ChArUco pose and homographies need 4; a
  // calibration wants many more per view.
  int min_corners = 6;
  // Corners closer than this to the image border are dropped: the sub-pixel refinement's window
  // would leave the image.
  double border_margin = 6.0;  // pixels
  void validate() const;       // throws core::Error naming the field
};

struct BoardDetection {
  std::vector<int> ids;                 // corner ids (BoardLayout::cornerPoint), ascending
  std::vector<Eigen::Vector2d> pixels;  // camera pixel of each corner
  int expected = 0;                     // the layout's corner count
  std::string problem;                  // why the board was not found; empty when found
  // A chessboard not found: the inner corners across and down of a whole chessboard one corner
  // larger or smaller each way that is in the image instead (a board given in the other
  // convention, squares for inner corners or back); 0 when none is.
  int seen_inner_x = 0;
  int seen_inner_y = 0;
  bool found() const { return problem.empty(); }
  bool complete() const { return found() && static_cast<int>(ids.size()) == expected; }
};

// `image`: 8-bit or 16-bit, one channel (16-bit is scaled to 8 bits for the detectors, the
// refinement runs on it too). Never throws for a board that is not there: the detection says
// why. Throws core::Error for an empty or multi-channel image or bad params/layout.
BoardDetection detectBoard(const cv::Mat& image, const BoardLayout& layout, const BoardDetectionParams& params = {});

// The board pose from its corners (cv::solvePnP, iterative, from the homography start) and
// the RMS reprojection error in pixels. Empty when the detection was not found or has fewer
// than 4 corners.
struct BoardPose {
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();
  double rms_px = 0.0;
};
std::optional<BoardPose> estimateBoardPose(const BoardDetection& detection, const BoardLayout& layout,
                                           const io::LensIntrinsics& camera);

}  // namespace binpick::calibration
