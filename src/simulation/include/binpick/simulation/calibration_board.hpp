#pragma once
// A printed calibration target for the virtual cell: a chessboard or a ChArUco board as a thin
// box with its print, the corners a calibration tool finds on it, and random poses in the rig's
// working volume from which both the camera and the projector see all of it.
//
// Board frame (metres), the frame of OpenCV's own object points for the board, so that a
// calibration tool can pair OpenCV's board definition with T_camera_board directly:
//   x along the rows of squares, y down the columns, z into the board (right-handed; a camera
//   looking at the print sees x to the right and y downwards when T_camera_board's rotation is
//   the identity). The print is the face z = 0, seen from -z; the body lies in 0 <= z <= thickness.
//   ChArUco (cv::aruco::CharucoBoard of OpenCV 4.6): the origin is the outer corner of the
//     top-left square (black); corner i is CharucoBoard::chessboardCorners[i], i.e.
//     ((c + 1) s, (r + 1) s, 0) for i = r (squares_x - 1) + c.
//   Chessboard: the origin is the first inner corner, next to the top-left square (black);
//     corner i is (c s, r s, 0) for i = r (squares_x - 1) + c, the row-major order of
//     cv::findChessboardCorners with pattern size (squares_x - 1, squares_y - 1) (a board that
//     looks the same turned half a turn may be listed from either end by that detector).
// Pixel coordinates put pixel centres at integers, as cv::cornerSubPix does. (OpenCV 4.6's
// cv::aruco::interpolateCornersCharuco returns its corners half a pixel off, opencv/opencv#25539;
// refine them again with cv::cornerSubPix before comparing them with the truth.)
//
// Value types and const member functions: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/io/point_cloud.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::simulation {

// The board types and their names are the calibration tools' own.
using calibration::BoardType;
using calibration::boardTypeFromName;
using calibration::boardTypeName;

// Defaults suit a 1280x1024 camera at about 0.9 m: 30 mm squares span some 50 pixels, a
// marker bit about 5.
struct BoardSpec {
  BoardType type = BoardType::Charuco;
  int squares_x = 9;                        // squares along the board's x (>= 3)
  int squares_y = 7;                        // squares along its y (>= 3)
  double square_size = 0.030;               // metres
  double marker_size = 0.022;               // ChArUco: side of the ArUco marker in each white square, metres
  std::string dictionary = "DICT_5X5_100";  // ChArUco: an OpenCV predefined dictionary by name
  double margin = 0.015;                    // white border around the squares, metres
  double thickness = 0.005;                 // metres
  double white_albedo = 0.85;               // diffuse reflectance of the paper and the white squares
  double black_albedo = 0.05;               // of the black squares and marker bits
  // The geometry the calibration tools detect (type, squares, markers, dictionary).
  calibration::BoardLayout layout() const;
  // Throws core::Error naming the field: "BoardLayout.marker_size ..." for the geometry,
  // "BoardSpec.thickness ..." for the rest.
  void validate() const;
};

// One corner a calibration tool measures: OpenCV's corner id and where it lies on the board.
struct BoardCorner {
  int id = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // board frame, z = 0
};

class CalibrationBoard {
 public:
  // The print is held as a texture of square texels no larger than `texel_size` metres (a
  // whole number of texels per square). Throws core::Error naming the field of a bad spec
  // or a non-positive texel_size.
  explicit CalibrationBoard(const BoardSpec& spec, double texel_size = 1e-4);

  const BoardSpec& spec() const { return spec_; }
  // A closed box, outward winding, in the board frame: the printed face z = 0 (normal -z) over
  // printedFace(), the back at z = thickness.
  const io::TriangleMesh& mesh() const { return mesh_; }
  // Every corner in id order.
  const std::vector<BoardCorner>& corners() const { return corners_; }
  // The printed face in the board frame (x, y), margin included: the board's outline.
  const Eigen::AlignedBox2d& printedFace() const { return face_; }
  double texelSize() const;

  // Diffuse reflectance of the print at (x, y) on the face, bilinear between texels; the
  // margin and anything off the squares is white.
  float albedo(const Eigen::Vector2d& xy) const;
  // The mean reflectance over the parallelogram centre + footprint * [-1/2, 1/2]^2 (the area a
  // camera pixel covers on the board), from samples x samples points.
  float meanAlbedo(const Eigen::Vector2d& centre, const Eigen::Matrix2d& footprint, int samples) const;

 private:
  BoardSpec spec_;
  io::TriangleMesh mesh_;
  std::vector<BoardCorner> corners_;
  Eigen::AlignedBox2d face_;
  Eigen::Vector2d squares_origin_;  // board (x, y) of the squares' top-left outer corner
  int texels_per_square_ = 0;
  std::vector<uint8_t> texture_;  // row-major, 0 black .. 255 white, top-left square first
  int texture_width_ = 0;
  int texture_height_ = 0;
};

// Where the rig sees a board corner. Pixel centres at integer coordinates, lens distortion
// included (LensIntrinsics::project); the projector pixel is what a decoded pattern reads there.
struct CornerObservation {
  int id = 0;
  Eigen::Vector2d camera_pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d projector_pixel = Eigen::Vector2d::Zero();
};

// The corners that both devices see on the board at T_camera_board: inside both images and on
// the side of the print that faces each device (the board alone hides none of its own corners).
std::vector<CornerObservation> observeCorners(const CalibrationBoard& board, const io::RigCalibration& rig,
                                              const Eigen::Isometry3d& T_camera_board);

// Random board poses in the working volume, for a calibration sequence.
struct BoardPoseParams {
  int count = 10;
  uint64_t seed = 1;
  double min_distance = 0.70;  // metres: camera z of the centre of the printed face
  double max_distance = 1.05;
  // Direction of the board centre off the camera axis: normalised image coordinates x/z, y/z,
  // each drawn in [-max_offset, max_offset].
  double max_offset = 0.2;
  double max_tilt = 0.698;              // radians (40 degrees) between the board normal and -z
  double max_in_plane_rotation = 0.52;  // radians (30 degrees) either way about the normal
  double image_margin = 10.0;           // pixels the board outline keeps from both image borders
  // The printed face must face both devices: cosine of the angle between its normal and the
  // direction to each device centre, at each corner of the outline.
  double min_facing_cosine = 0.3;
  int max_attempts = 1000;  // draws per pose before giving up
  void validate() const;    // throws core::Error naming the field
};

// Whether the whole board outline lies `image_margin` pixels inside the camera image and the
// projector image, in front of both, and the print faces both by `min_facing_cosine`.
bool boardInView(const CalibrationBoard& board, const io::RigCalibration& rig, const Eigen::Isometry3d& T_camera_board,
                 double image_margin, double min_facing_cosine);

// `params.count` poses T_camera_board. Each draw takes a distance, an offset, a tilt about a
// random axis in the image plane and an in-plane rotation; a draw that fails boardInView is
// dropped and the next one taken from the same generator, so a seed gives the same poses on any
// machine (and the first k poses do not depend on count). Throws core::Error on bad params
// or when max_attempts draws in a row fail (the board is too large for the views).
std::vector<Eigen::Isometry3d> randomBoardPoses(const CalibrationBoard& board, const io::RigCalibration& rig,
                                                const BoardPoseParams& params);

}  // namespace binpick::simulation
