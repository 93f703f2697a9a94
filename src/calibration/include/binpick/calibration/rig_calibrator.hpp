#pragma once
// Camera + projector calibration from board views (rig_views.hpp):
// 1. the camera's intrinsics and distortion (cv::calibrateCamera) from every corner it found;
// 2. the projector's, as an inverse camera of the pattern set's size, from the corners that have
//    a projector pixel;
// 3. the extrinsics R, T = T_projector_camera (cv::stereoCalibrate) from the corners both have,
//    refining both devices' intrinsics from steps 1 and 2 at the same time by default: each
//    board pose is then pinned by both devices at once, which on the virtual cell lowered the
//    translation, rotation and principal point errors against holding the intrinsics fixed
//    (docs/calibration.md has the figures).
// Every view gets its reprojection RMS in both images under the final rig. A view whose RMS
// exceeds max(outlier_floor_px, outlier_factor x the median view's) is an outlier: reported,
// and with drop_outliers left out and the calibration computed once more without it.
// Views that cannot be used (board not found, too few corners) are skipped with a warning naming
// them; too few usable views is an error naming every unusable view and why.
// Stateless: thread-safe.
#include <string>
#include <vector>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/rig_views.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::calibration {

struct RigCalibrationParams {
  int min_views = 8;              // usable views needed (after dropping outliers)
  int min_corners = 10;           // corners with both a camera and a projector pixel, per view
  double outlier_floor_px = 0.5;  // RMS below this never makes a view an outlier
  double outlier_factor = 3.0;    // ... nor below this multiple of the median view's RMS
  bool drop_outliers = false;
  // k3 (the sixth-order radial term) is kept at 0: a board that does not reach the image corners
  // cannot tell it from k1, k2, and a free k3 then bends the model where there are no corners.
  bool fix_k3 = true;
  // Step 3 with CALIB_USE_INTRINSIC_GUESS (true) or CALIB_FIX_INTRINSIC (false).
  bool refine_intrinsics_in_stereo = true;
  // A final stereo RMS above this is reported as a warning: the calibration is written, but
  // something (focus, board flatness, a moving board) is wrong.
  double warn_rms_px = 1.0;
  void validate() const;  // throws core::Error naming the field
};

struct RigCalibrationTimings {  // milliseconds
  double camera = 0.0;
  double projector = 0.0;
  double stereo = 0.0;
};

struct RigCalibrationResult {
  io::RigCalibration rig;
  io::RigCalibrationQuality quality;  // per view, in the order given; ready for calib.yaml
  std::vector<std::string> warnings;  // one line each, naming the view
  RigCalibrationTimings timings;      // of the final solve
};

// Throws core::Error when fewer than min_views views are usable (naming each unusable view and
// why), when dropping the outliers leaves too few, when the views disagree on the camera or
// projector size, or when OpenCV cannot solve the calibration.
RigCalibrationResult calibrateRig(const std::vector<RigView>& views, const BoardLayout& layout,
                                  const RigCalibrationParams& params = {});

}  // namespace binpick::calibration
