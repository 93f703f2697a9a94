#pragma once
// Internal to binpick::calibration: one device's own solve (cv::calibrateCamera) with chosen
// distortion terms, the per-term report, and the board's directions in the device's views.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"
#include "binpick/io/lens.hpp"

namespace binpick::calibration::detail {

struct LensFit {
  cv::Mat matrix;
  cv::Mat distortion;
  double rms = 0.0;
  cv::Mat sd;                                  // standard deviations of the intrinsics, OpenCV's order
  std::vector<Eigen::Vector3d> board_normals;  // per view, the board's z axis in the device frame
};

// One device's corners: per view, board points and their pixels.
struct LensData {
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> images;
  cv::Size size;
  const char* device = "camera";  // for error messages
};

// The fit with `terms`, and its report. A solve started from zero distortion can stop in a local
// minimum worse than a fit with fewer terms (on real views the projector with p1,p2 fitted ended
// at 0.87 px, above the 0.86 px of the fit holding k1): the richer model is then solved again from
// each better fit with one term fewer, and the best of them is kept, so that fitting a term never
// ends worse than holding it. The report says when this happened (LensFitReport::restarted).
// Throws core::Error when OpenCV cannot solve.
LensFit fitLensReported(const LensData& data, const DistortionTerms& terms, LensFitReport& report);

io::LensIntrinsics lensFrom(const LensFit& fit, cv::Size size);

}  // namespace binpick::calibration::detail
