#pragma once
// The OpenCV part of the rig calibration: views' corners as OpenCV's point lists, and the three
// solves (camera, projector, stereo) with every view's RMS under the final rig.
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/calibration/rig_calibrator.hpp"

namespace binpick::calibration::detail {

// One usable view's corners. The camera solve takes every corner the camera found; the
// projector and stereo solves the corners that also have a projector pixel.
struct ViewPoints {
  std::vector<cv::Point3f> camera_object;
  std::vector<cv::Point2f> camera_image;
  std::vector<cv::Point3f> shared_object;
  std::vector<cv::Point2f> shared_camera;
  std::vector<cv::Point2f> shared_projector;
};

ViewPoints viewPoints(const RigView& view, const BoardLayout& layout);

struct RigSolution {
  io::RigCalibration rig;
  double camera_rms_px = 0.0;
  double projector_rms_px = 0.0;
  double stereo_rms_px = 0.0;
  LensFitReport camera_fit;
  LensFitReport projector_fit;
  std::vector<double> view_camera_rms_px;  // per view, under the final rig
  std::vector<double> view_projector_rms_px;
  RigCalibrationTimings timings;
};

// Throws core::Error when OpenCV fails or gives a non-finite or invalid rig.
RigSolution solveRig(const std::vector<ViewPoints>& views, cv::Size camera_size, cv::Size projector_size,
                     const RigCalibrationParams& params);

}  // namespace binpick::calibration::detail
