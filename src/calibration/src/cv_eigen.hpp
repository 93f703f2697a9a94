#pragma once
// Internal to binpick::calibration: OpenCV's rotation matrices and vectors as Eigen poses.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace binpick::calibration::detail {

// R: 3x3, t: 3 values, both CV_64F; R is taken as it is (not re-orthonormalised).
inline Eigen::Isometry3d isometryFromCv(const cv::Mat& R, const cv::Mat& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.matrix()(r, c) = R.at<double>(r, c);
    T.matrix()(r, 3) = t.at<double>(r);
  }
  return T;
}

}  // namespace binpick::calibration::detail
