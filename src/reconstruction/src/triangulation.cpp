// Triangulator: the calibration's tables, input checks, and the parallel loop over image rows.
#include "binpick/reconstruction/triangulation.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "epipolar_residual.hpp"
#include "triangulation_rows.hpp"
#include "triangulation_tables.hpp"

namespace binpick::reconstruction {

struct Triangulator::Tables {
  detail::CameraRays rays;
  detail::ProjectorTables projector;
  detail::RigGeometry geometry;
  detail::RigFrames frames;  // for the calibration's residual field
};

namespace {

// The calibration's fit is measured on every 4th pixel of every 4th row: up to 64 samples per
// tile of its residual field, for a few milliseconds per megapixel.
constexpr int kFitSamplingStride = 4;

// Image row y's epipolar limits: a pixel read along its stripe has its projector column and row
// each somewhere in a run of codes, about (run - 1) / 2 codes from where it was placed
// (stripe_reading.hpp).
void stripeLimits(const DecodedCapture& decoded, int y, double max_epipolar_error, float* limit_scale_sq) {
  const uint8_t* run = decoded.stripe_run.ptr<uint8_t>(y);
  for (int x = 0; x < decoded.width; ++x) {
    const double limit = max_epipolar_error + 0.5 * std::max(0, run[x] - 1) * decoded.code_step;
    limit_scale_sq[x] = static_cast<float>((limit * limit) / (max_epipolar_error * max_epipolar_error));
  }
}

void requireImage(const cv::Mat& image, int type, const DecodedCapture& decoded, const char* name) {
  if (image.rows == decoded.height && image.cols == decoded.width && image.type() == type) return;
  throw core::Error(std::string("Triangulator::triangulate: decoded.") + name + " must be " +
                    std::to_string(decoded.width) + "x" + std::to_string(decoded.height) + " of type " +
                    std::to_string(type) + " (got " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                    " of type " + std::to_string(image.type()) + ")");
}

void checkDecoded(const DecodedCapture& decoded, const io::LensIntrinsics& camera) {
  if (decoded.width != camera.width || decoded.height != camera.height) {
    throw core::Error("Triangulator::triangulate: the decoded capture is " + std::to_string(decoded.width) + "x" +
                      std::to_string(decoded.height) + " but the camera is " + std::to_string(camera.width) + "x" +
                      std::to_string(camera.height));
  }
  requireImage(decoded.column, CV_32FC1, decoded, "column");
  requireImage(decoded.status, CV_8UC1, decoded, "status");
  if (!decoded.row.empty()) requireImage(decoded.row, CV_32FC1, decoded, "row");
  if (!decoded.stripe_run.empty()) requireImage(decoded.stripe_run, CV_8UC1, decoded, "stripe_run");
}

}  // namespace

void TriangulationParams::validate() const {
  core::requireField(std::isfinite(max_epipolar_error) && max_epipolar_error > 0.0, "TriangulationParams",
                     "max_epipolar_error", "positive and finite", max_epipolar_error);
  core::requireField(std::isfinite(max_calibration_residual) && max_calibration_residual >= 0.0, "TriangulationParams",
                     "max_calibration_residual", ">= 0 and finite", max_calibration_residual);
  core::requireField(threads >= 0, "TriangulationParams", "threads", ">= 0", threads);
}

Triangulator::Triangulator(const io::RigCalibration& rig, const TriangulationParams& params)
    : rig_(rig), params_(params) {
  rig_.validate();
  params_.validate();
  const int threads = core::resolveThreadCount(params_.threads);
  auto tables = std::make_unique<Tables>();
  tables->rays = detail::buildCameraRays(rig_.camera, threads);
  const Eigen::Vector3d camera_centre = rig_.T_projector_camera.translation();
  const detail::EpipolarPencil pencil = detail::makeEpipolarPencil(camera_centre);
  tables->projector = detail::buildProjectorTables(rig_.projector, pencil, camera_centre, threads);
  tables->geometry = detail::makeRigGeometry(rig_, pencil, params_.max_epipolar_error);
  tables->geometry.column_when_inconsistent = params_.column_when_row_inconsistent;
  tables->frames = detail::rigFrames(rig_);
  tables_ = std::move(tables);
}

Triangulator::~Triangulator() = default;
Triangulator::Triangulator(Triangulator&&) noexcept = default;
Triangulator& Triangulator::operator=(Triangulator&&) noexcept = default;

const io::RigCalibration& Triangulator::rig() const { return rig_; }

TriangulatedCloud Triangulator::triangulate(const DecodedCapture& decoded) const {
  checkDecoded(decoded, rig_.camera);
  const int width = decoded.width, height = decoded.height;
  const int threads = core::resolveThreadCount(params_.threads);
  TriangulatedCloud result;
  result.cloud.width = width;
  result.cloud.height = height;
  // resize() leaves Eigen's vectors uninitialised: the image-row loop writes every element.
  result.cloud.points.resize(static_cast<std::size_t>(width) * height);
  result.status.create(height, width, CV_8UC1);
  result.depth_per_projector_px.create(height, width, CV_32FC1);
  const Tables& tables = *tables_;
  const bool with_rows = !decoded.row.empty();
  detail::EpipolarResidualField field;
  if (with_rows) {
    detail::FitSampling sampling;
    sampling.stride = kFitSamplingStride;
    sampling.limit_px = params_.max_epipolar_error;
    sampling.max_residual_px = params_.max_calibration_residual;
    sampling.threads = threads;
    detail::FitMeasurement measured =
        detail::measureFit(tables.frames, tables.rays, tables.projector.undistort, decoded, sampling);
    result.calibration_fit = measured.fit;
    field = std::move(measured.field);
  }
#pragma omp parallel num_threads(threads)
  {
    detail::TriangulationScratch scratch(width);
    std::vector<float> expected_offset(with_rows ? width : 0);
    std::vector<float> limit_scale_sq(with_rows ? width : 0, 1.0f);
#pragma omp for schedule(static)
    for (int y = 0; y < height; ++y) {
      const std::size_t offset = static_cast<std::size_t>(y) * width;
      detail::TriangulationImageRowInput in;
      in.width = width;
      in.ray_x = tables.rays.x.data() + offset;
      in.ray_y = tables.rays.y.data() + offset;
      in.column = decoded.column.ptr<float>(y);
      in.row = with_rows ? decoded.row.ptr<float>(y) : nullptr;
      in.status = decoded.status.ptr<uint8_t>(y);
      const detail::TriangulationImageRowOutput out{result.cloud.points.data() + offset, result.status.ptr<uint8_t>(y),
                                                    result.depth_per_projector_px.ptr<float>(y)};
      if (with_rows) {
        field.rowOffsets(y, width, expected_offset.data());
        in.expected_offset = expected_offset.data();
        if (!decoded.stripe_run.empty()) stripeLimits(decoded, y, params_.max_epipolar_error, limit_scale_sq.data());
        in.limit_scale_sq = limit_scale_sq.data();
        detail::triangulateImageRowWithProjectorRows(tables.geometry, tables.projector, in, scratch, out);
      } else {
        detail::triangulateImageRowColumnOnly(tables.geometry, tables.projector, in, scratch, out);
      }
    }
  }
  return result;
}

}  // namespace binpick::reconstruction
