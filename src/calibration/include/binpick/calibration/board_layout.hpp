#pragma once
// The geometry of a printed calibration board, as the calibration tools see it: the type, the
// squares, the ArUco dictionary of a ChArUco board, and where each corner lies on the board.
//
// Board frame (metres), the frame of OpenCV's own object points: x along the rows of squares,
// y down the columns, z into the board; the print is the face z = 0.
//   ChArUco (cv::aruco::CharucoBoard): corner i = ((c + 1) s, (r + 1) s, 0), i = r (squares_x - 1)
//     + c; the origin is the outer corner of the top-left square.
//   Chessboard: corner i = (c s, r s, 0), the row-major order of cv::findChessboardCorners with
//     pattern size (squares_x - 1, squares_y - 1); the origin is the first inner corner.
// Value type and pure functions: thread-safe.
#include <Eigen/Core>
#include <string>

namespace binpick::calibration {

enum class BoardType { Chessboard, Charuco };

// "chessboard" or "charuco"; boardTypeFromName throws core::Error on another name.
std::string boardTypeName(BoardType type);
BoardType boardTypeFromName(const std::string& name);

// OpenCV's predefined ArUco dictionaries by the name of their enumerator ("DICT_5X5_100").
// arucoDictionaryId gives -1 for an unknown name; arucoDictionarySize the markers in a known id.
int arucoDictionaryId(const std::string& name);
int arucoDictionarySize(int id);
std::string arucoDictionaryNames();  // comma-separated, for error messages

// Defaults: the board of the virtual cell (9 x 7 squares of 30 mm, 22 mm markers).
struct BoardLayout {
  BoardType type = BoardType::Charuco;
  int squares_x = 9;                        // squares along the board's x (>= 3)
  int squares_y = 7;                        // squares along its y (>= 3)
  double square_size = 0.030;               // metres
  double marker_size = 0.022;               // ChArUco: marker side, metres (< square_size)
  std::string dictionary = "DICT_5X5_100";  // ChArUco only

  // Throws core::Error "BoardLayout.FIELD must be ..."; a ChArUco board needs a dictionary
  // holding at least one marker per white square.
  void validate() const;
  int cornerCount() const { return (squares_x - 1) * (squares_y - 1); }
  // Corner `id` (0 <= id < cornerCount()) in the board frame, z = 0.
  Eigen::Vector3d cornerPoint(int id) const;
};

}  // namespace binpick::calibration
