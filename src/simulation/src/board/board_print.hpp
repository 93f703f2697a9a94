#pragma once
// What is printed on a calibration board, and where its corners are, in OpenCV's own terms so
// that the rendered board is the one OpenCV's detectors and object points describe. Internal to
// binpick::simulation. Pure functions: thread-safe.
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/simulation/calibration_board.hpp"

namespace binpick::simulation::detail {

// The squares area of the board (margin excluded) as an 8-bit image, 0 black and 255 white,
// `texels_per_square` texels per square side: squares_x * t wide, squares_y * t high. Texel
// (col, row) covers the board's x, y from the squares' top-left outer corner + (col, row) * s / t
// to + (col + 1, row + 1) * s / t, s the square size. The top-left square is black.
cv::Mat drawBoardPrint(const BoardSpec& spec, int texels_per_square);

// The corners in id order, in the board frame of calibration_board.hpp.
std::vector<BoardCorner> boardCornerPoints(const BoardSpec& spec);

// Board (x, y) of the squares' top-left outer corner: (0, 0) for ChArUco, (-s, -s) for a
// chessboard, whose origin is its first inner corner.
Eigen::Vector2d squaresOrigin(const BoardSpec& spec);

}  // namespace binpick::simulation::detail
