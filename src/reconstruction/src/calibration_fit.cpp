// measureCalibrationFit: how far each decoded pixel's projector ray misses its camera ray.
//
// Frames as in triangulation_rows.cpp: in the projector frame the camera ray of a pixel is
// C + t d with C the camera centre and d = R (a, b, 1), (a, b) its undistorted normalised
// coordinates, so t is the point's camera z; the projector ray of the decoded (column, row) is
// s (u, v, 1), (u, v) undistorted normalised projector coordinates, s the projector z.
#include "binpick/reconstruction/calibration_fit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/reconstruction/pixel_status.hpp"
#include "triangulation_tables.hpp"

namespace binpick::reconstruction {
namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
// Rays closer to parallel than this (the sine of their angle, squared) meet nowhere useful.
constexpr double kMinSineSquared = 1e-12;

struct PixelFit {
  float epipolar_px = kNaNf;
  float gap_m = kNaNf;
};

// The rig as the per-pixel measures use it.
struct RigFrames {
  Eigen::Matrix3d r;  // camera -> projector rotation
  Eigen::Vector3d c;  // the camera centre in the projector frame
  double projector_fx = 1.0, projector_fy = 1.0;
};

// The decoded (u, v) lies on the camera ray's image in the projector, the epipolar line
// n . (u, v, 1) = 0 with n = C x d, when the rays meet. In pixels (fx u, fy v) the line's normal
// is (nx / fx, ny / fy).
double epipolarDistancePx(const RigFrames& rig, const Eigen::Vector3d& d, const Eigen::Vector3d& w) {
  const Eigen::Vector3d n = rig.c.cross(d);
  const double line = std::hypot(n.x() / rig.projector_fx, n.y() / rig.projector_fy);
  return std::abs(n.dot(w)) / line;
}

// The closest approach of C + t d and s w: NaN unless it lies in front of both devices.
double rayGapMetres(const RigFrames& rig, const Eigen::Vector3d& d, const Eigen::Vector3d& w) {
  const double dd = d.dot(d), dw = d.dot(w), ww = w.dot(w);
  const double dc = d.dot(rig.c), wc = w.dot(rig.c);
  const double denominator = dd * ww - dw * dw;  // |d x w|^2
  if (!(denominator > kMinSineSquared * dd * ww)) return kNaNf;
  const double t = (dw * wc - ww * dc) / denominator;
  const double s = (dd * wc - dw * dc) / denominator;
  if (!(t > 0.0 && s > 0.0)) return kNaNf;
  return (rig.c + t * d - s * w).norm();
}

PixelFit fitOfPixel(const RigFrames& rig, float a, float b, const float uv[2]) {
  PixelFit fit;
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(uv[0]) || !std::isfinite(uv[1])) return fit;
  const Eigen::Vector3d d = rig.r * Eigen::Vector3d(a, b, 1.0);
  const Eigen::Vector3d w(uv[0], uv[1], 1.0);
  fit.epipolar_px = static_cast<float>(epipolarDistancePx(rig, d, w));
  fit.gap_m = static_cast<float>(rayGapMetres(rig, d, w));
  return fit;
}

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

// Every pixel's measures, NaN where the pixel has no decoded column and row inside the
// projector image (the margin triangulation accepts included).
std::vector<PixelFit> fitOfPixels(const RigFrames& rig, const detail::CameraRays& rays,
                                  const detail::LookupGrid<2>& undistort, const DecodedCapture& decoded, int threads) {
  std::vector<PixelFit> fits(static_cast<std::size_t>(decoded.width) * decoded.height);
  const auto grid = undistort.view();
  constexpr auto kValid = static_cast<uint8_t>(PixelStatus::Valid);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int y = 0; y < decoded.height; ++y) {
    const float* column = decoded.column.ptr<float>(y);
    const float* row = decoded.row.ptr<float>(y);
    const uint8_t* status = decoded.status.ptr<uint8_t>(y);
    for (int x = 0; x < decoded.width; ++x) {
      if (status[x] != kValid) continue;
      const auto at = grid.locate(column[x], row[x]);  // NaN rows fall outside
      if (!at.inside) continue;
      float uv[2];
      grid.interpolate(at.cell, at.fx, at.fy, uv);
      const std::size_t i = static_cast<std::size_t>(y) * decoded.width + x;
      fits[i] = fitOfPixel(rig, rays.x[i], rays.y[i], uv);
    }
  }
  return fits;
}

// The upper median: half the values are at most it.
double median(std::vector<float> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

CalibrationFit summarise(const std::vector<PixelFit>& fits, double limit_px) {
  std::vector<float> epipolar, gaps;
  std::size_t beyond = 0;
  for (const PixelFit& fit : fits) {
    if (std::isnan(fit.epipolar_px)) continue;
    epipolar.push_back(fit.epipolar_px);
    beyond += fit.epipolar_px > limit_px ? 1 : 0;
    if (!std::isnan(fit.gap_m)) gaps.push_back(fit.gap_m);
  }
  CalibrationFit result;
  result.epipolar_limit_px = limit_px;
  result.pixels = epipolar.size();
  result.pixels_with_gap = gaps.size();
  result.beyond_limit_share = epipolar.empty() ? 0.0 : static_cast<double>(beyond) / epipolar.size();
  result.median_epipolar_px = median(std::move(epipolar));
  result.median_gap_mm = 1000.0 * median(std::move(gaps));
  return result;
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
  const int threads = core::resolveThreadCount(params.threads);
  const RigFrames frames{rig.T_projector_camera.linear(), rig.T_projector_camera.translation(), rig.projector.fx,
                         rig.projector.fy};
  const detail::CameraRays rays = detail::buildCameraRays(rig.camera, threads);
  const detail::LookupGrid<2> undistort = detail::buildUndistortGrid(rig.projector, threads);
  return summarise(fitOfPixels(frames, rays, undistort, decoded, threads), params.max_epipolar_error);
}

}  // namespace binpick::reconstruction
