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
// Each device's own solve is also run once more per distortion term with that term toggled
// (freed when held, held when free): the RMS either way, the term's value and its standard
// deviation tell whether the term is warranted.
// Every view gets its reprojection RMS in both images under the final rig. A view whose RMS
// exceeds max(outlier_floor_px, outlier_factor x the median view's) is an outlier: reported,
// and with drop_outliers left out and the calibration computed once more without it.
// Views that cannot be used (board not found, too few corners) are skipped with a warning naming
// them; too few usable views is an error naming every unusable view and why.
// Stateless: thread-safe.
#include <string>
#include <vector>

#include <array>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/distortion_terms.hpp"
#include "binpick/calibration/rig_views.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::calibration {

struct RigCalibrationParams {
  // Usable views needed (after dropping outliers): below, an error. Three board poses are the
  // least a lens solve needs; fewer than recommended_views are calibrated with a warning naming
  // the intrinsics they leave poorly determined.
  int min_views = 3;
  int recommended_views = 8;
  int min_corners = 10;  // corners with both a camera and a projector pixel, per view
  // RMS below this never makes a view an outlier. Low enough that a view several times worse
  // than clean ones of 0.05 px (a blurred view at 0.4 px) is flagged, high enough that the
  // spread of clean views (up to some 0.08 px) is not.
  double outlier_floor_px = 0.15;
  double outlier_factor = 3.0;  // ... nor below this multiple of the median view's RMS
  bool drop_outliers = false;
  // The distortion terms each device's fit may change (distortion_terms.hpp); k3 is held at 0 by
  // default. In the stereo step a term is refined only when both devices fit it; a term only
  // one of them fits keeps the value of that device's own solve there.
  DistortionTerms camera_distortion;
  DistortionTerms projector_distortion;
  // Step 3 with CALIB_USE_INTRINSIC_GUESS (true) or CALIB_FIX_INTRINSIC (false).
  bool refine_intrinsics_in_stereo = true;
  // An own solve's standard deviation above these shares (of the focal length; of the image's
  // width for the principal point) names the intrinsic as poorly determined; a principal point
  // poorly determined is warned about on its own, with the remedy.
  double max_focal_sd_share = 0.005;
  double max_principal_point_sd_share = 0.005;
  // What that warning names as the remedy: more tilt when the board's normals stay within this
  // angle of each other, a board filling more of the image when it spans less than this share of
  // the camera image's width on average.
  double min_tilt_spread_deg = 30.0;
  double min_board_span = 0.6;
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

// What one distortion term buys: the device's own solve with the term fitted and with it held
// at 0, the other terms as chosen. A term is warranted when fitting it lowers the RMS and its
// value stands several standard deviations clear of 0.
struct TermResidual {
  bool chosen = false;            // in LensFitReport::terms (then one of the two RMS is rms_px)
  double rms_fitted_px = 0.0;     // the own solve with the term fitted ...
  double rms_held_px = 0.0;       // ... and held at 0
  std::array<double, 2> value{};  // its value when fitted (p1, p2 for the tangential pair) ...
  std::array<double, 2> sd{};     // ... and standard deviation
};

// One device's own solve (step 1 or 2) with the chosen terms, and once more per term with that
// term toggled (held when chosen, freed from the chosen fit when not). Fitting a term never ends
// worse than holding it: when the solve from zero distortion stops above a fit with one chosen
// term held (a local minimum), it is solved again from that fit and the better one is kept.
struct LensFitReport {
  DistortionTerms terms;
  io::LensIntrinsics lens;  // the own solve's result (the rig's lens after the stereo step may differ)
  double rms_px = 0.0;
  double scratch_rms_px = 0.0;  // the solve from zero distortion (rms_px unless restarted)
  std::string restarted_from;   // the term held in the fit the solve restarted from; empty if none
  // The largest angle between the board's normals in two views: small when the poses are alike.
  double board_normal_spread_deg = 0.0;
  // Standard deviation of fx, fy, cx, cy, k1, k2, p1, p2, k3 from the solve's Jacobian (0 for a
  // term held), in pixels and the terms' units.
  std::array<double, 9> sd{};
  std::array<TermResidual, kDistortionTermCount> per_term;  // in kDistortionTermNames' order
  const TermResidual& k3() const { return per_term[3]; }
};

struct RigCalibrationResult {
  io::RigCalibration rig;
  LensFitReport camera_fit;  // of the final solve
  LensFitReport projector_fit;
  io::RigCalibrationQuality quality;  // per view, in the order given; ready for calib.yaml
  std::vector<std::string> warnings;  // one line each, naming the view
  RigCalibrationTimings timings;      // of the final solve
};

// Fewer usable views than recommended_views, or principal points poorly pinned, add a warning.
// Throws core::Error when fewer than min_views views are usable (naming each unusable view and
// why), when dropping the outliers leaves too few, when the views disagree on the camera or
// projector size, or when OpenCV cannot solve the calibration.
RigCalibrationResult calibrateRig(const std::vector<RigView>& views, const BoardLayout& layout,
                                  const RigCalibrationParams& params = {});

}  // namespace binpick::calibration
