#pragma once
// A hand-eye views directory and the board poses in its images (docs/hand-eye.md):
//   DIR/poses.txt   the robot poses (robot_pose_file.hpp)
//   DIR/VIEW.png    each view's camera image, 8- or 16-bit grey
// Every view needs both. A view whose board is not found, is less than half in the image, or
// whose pose does not fit its corners is left out with the reason; the hand-eye solve then
// needs enough of the rest. Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/hand_eye.hpp"
#include "binpick/core/orientation.hpp"
#include "binpick/io/lens.hpp"

namespace binpick::calibration {

struct HandEyeViewFile {
  std::string name;
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity();
  std::string image_path;
  std::optional<core::Orientation> orientation;  // how poses.txt wrote the pose, when from a file
};

// Views in poses.txt order. Throws core::Error naming the view for a pose without its image
// or an image (DIR/*.png) without a pose, and whatever readRobotPoseFile throws.
std::vector<HandEyeViewFile> listHandEyeViews(const std::string& directory);

struct BoardViewParams {
  BoardDetectionParams detection;
  // A board partly out of the image still gives a pose from the corners seen, but one from a
  // corner of the board is poorly constrained: below this share of the corners the view is left
  // out, above it the view is used and noted.
  double min_corner_share = 0.5;
  double max_rms_px = 1.0;  // a pose fitting its corners worse than this is left out
  void validate() const;    // throws core::Error naming the field
};

struct MeasuredView {
  std::string name;
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity();
  int corners = 0;                                  // corners found
  int expected = 0;                                 // corners on the board
  double rms_px = 0.0;                              // the board pose's reprojection RMS
  std::optional<Eigen::Isometry3d> T_camera_board;  // empty: the view is not usable
  std::string problem;                              // why it is not usable
  std::string note;                                 // a caveat of a usable view (a partial board)
  std::optional<core::Orientation> orientation;     // HandEyeViewFile::orientation
  bool usable() const { return T_camera_board.has_value(); }
};

// Reads and measures one view's image. Throws core::Error naming the view for an unreadable
// image, one that is not 8- or 16-bit grey, or one whose size is not the camera's.
MeasuredView measureView(const HandEyeViewFile& file, const BoardLayout& layout, const io::LensIntrinsics& camera,
                         const BoardViewParams& params = {});

// The usable views solved. Throws core::Error listing every unusable view with its reason
// when fewer than params.min_views are usable, and whatever solveHandEye throws; and, before
// solving, when poses written in a convention of degrees hold angles all below 3.2 that fit read
// as radians ("the robot orientations look like radians").
HandEyeResult solveMeasuredViews(const std::vector<MeasuredView>& views, const HandEyeParams& params);

}  // namespace binpick::calibration
