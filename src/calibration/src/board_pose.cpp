// The board pose seen by a calibrated camera: planar PnP, then Levenberg-Marquardt refinement.
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "binpick/calibration/board_detection.hpp"
#include "cv_eigen.hpp"

namespace binpick::calibration {
namespace {

cv::Mat cameraMatrix(const io::LensIntrinsics& lens) {
  return (cv::Mat_<double>(3, 3) << lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0);
}

Eigen::Isometry3d isometry(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat rotation;
  cv::Rodrigues(rvec, rotation);
  return detail::isometryFromCv(rotation, tvec);
}

}  // namespace

std::optional<BoardPose> estimateBoardPose(const BoardDetection& detection, const BoardLayout& layout,
                                           const io::LensIntrinsics& camera) {
  if (!detection.found() || detection.ids.size() < 4) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (std::size_t i = 0; i < detection.ids.size(); ++i) {
    const Eigen::Vector3d p = layout.cornerPoint(detection.ids[i]);
    object.emplace_back(p.x(), p.y(), p.z());
    image.emplace_back(detection.pixels[i].x(), detection.pixels[i].y());
  }
  const cv::Mat K = cameraMatrix(camera);
  const cv::Mat distortion(std::vector<double>(camera.distortion.begin(), camera.distortion.end()), true);
  cv::Mat rvec, tvec;
  // IPPE is the planar solver: no ambiguity from a poor start for a board seen head-on.
  if (!cv::solvePnP(object, image, K, distortion, rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    return std::nullopt;
  }
  cv::solvePnPRefineLM(object, image, K, distortion, rvec, tvec);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, rvec, tvec, K, distortion, projected);
  double squared = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const cv::Point2d d = projected[i] - image[i];
    squared += d.dot(d);
  }
  return BoardPose{isometry(rvec, tvec), std::sqrt(squared / static_cast<double>(image.size()))};
}

}  // namespace binpick::calibration
