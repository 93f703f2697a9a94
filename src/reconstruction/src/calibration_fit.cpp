// measureCalibrationFit: every decoded pixel's fit (epipolar_residual.hpp measures it).
#include "calibration_fit.hpp"

#include <string>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "epipolar_residual.hpp"
#include "triangulation_tables.hpp"

namespace binpick::reconstruction {
namespace {

void checkDecoded(const DecodedCapture& decoded, const io::LensIntrinsics& camera) {
  const bool sizes = decoded.width == camera.width && decoded.height == camera.height;
  const auto fits = [&](const cv::Mat& image, int type) {
    return image.rows == decoded.height && image.cols == decoded.width && image.type() == type;
  };
  if (!sizes || !fits(decoded.column, CV_32FC1) || !fits(decoded.status, CV_8UC1) ||
      (!decoded.row.empty() && !fits(decoded.row, CV_32FC1))) {
    throw core::Error("measureCalibrationFit: the decoded capture must be the camera's " +
                      std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                      " (column, row CV_32FC1, status CV_8UC1)");
  }
}

}  // namespace

CalibrationFit measureCalibrationFit(const io::RigCalibration& rig, const DecodedCapture& decoded,
                                     const TriangulationParams& params) {
  rig.validate();
  params.validate();
  checkDecoded(decoded, rig.camera);
  if (decoded.row.empty()) {
    CalibrationFit fit;
    fit.epipolar_limit_px = params.max_epipolar_error;
    return fit;
  }
  detail::FitSampling sampling;
  sampling.limit_px = params.max_epipolar_error;
  sampling.max_residual_px = params.max_calibration_residual;
  sampling.threads = core::resolveThreadCount(params.threads);
  const detail::CameraRays rays = detail::buildCameraRays(rig.camera, sampling.threads);
  const detail::LookupGrid<2> undistort = detail::buildUndistortGrid(rig.projector, sampling.threads);
  return detail::measureFit(detail::rigFrames(rig), rays, undistort, decoded, sampling).fit;
}

}  // namespace binpick::reconstruction
