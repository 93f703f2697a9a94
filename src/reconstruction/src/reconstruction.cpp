// Reconstructor: the stages in order, timed.
#include "binpick/reconstruction/reconstruction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"

namespace binpick::reconstruction {
namespace {

void requireCameraSize(const io::Capture& capture, const io::RigCalibration& rig) {
  const io::CaptureMetadata& m = capture.metadata;
  if (m.image_width == rig.camera.width && m.image_height == rig.camera.height) return;
  throw core::Error("capture: images are " + std::to_string(m.image_width) + "x" + std::to_string(m.image_height) +
                    " but the calibration's camera is " + std::to_string(rig.camera.width) + "x" +
                    std::to_string(rig.camera.height));
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// A pattern set made for another projector codes columns the calibration does not have: every
// decoded coordinate would be scaled wrongly (and many land outside the projector).
void requireProjectorSize(const io::Capture& capture, const io::RigCalibration& rig) {
  const io::PatternSetSpec& spec = capture.metadata.pattern_set;
  if (spec.projector_width == rig.projector.width && spec.projector_height == rig.projector.height) return;
  throw core::Error("capture: the pattern set is for a " + sizeText(spec.projector_width, spec.projector_height) +
                    " projector but the calibration's projector is " +
                    sizeText(rig.projector.width, rig.projector.height));
}

// Triangulating from columns alone intersects each camera ray with a column's plane of light,
// which holds the projector's centre and its column direction (y). The depth resolution comes
// from the baseline's component across the columns (x): a baseline along the columns lies in
// every such plane, and the intersection degenerates.
constexpr double kMinBaselineAcrossColumns = 0.5;  // share of the baseline's length

// The share of the camera-projector baseline across the projector's columns: how much depth the
// column alone carries (1: all of it, a camera beside the projector).
double baselineAcrossColumns(const io::RigCalibration& rig) {
  const Eigen::Vector3d baseline = rig.T_projector_camera.translation();  // camera centre, projector frame
  const double length = baseline.norm();
  return length > 0.0 ? std::fabs(baseline.x()) / length : 1.0;
}

std::vector<std::string> geometryWarnings(const io::Capture& capture, const io::RigCalibration& rig) {
  if (capture.metadata.pattern_set.row_codes) return {};
  const double across = baselineAcrossColumns(rig);
  if (across >= kMinBaselineAcrossColumns) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "column-only capture with the camera-projector baseline nearly along the projector's columns "
                "(%.0f%% of it across them, %.0f degrees from the rows): triangulation from columns is "
                "ill-conditioned; code rows too, or mount the camera beside the projector",
                100.0 * across, std::acos(std::min(1.0, across)) * 180.0 / M_PI);
  return {text};
}

// A pixel whose row did not decode keeps its column only where the column carries the depth: on
// a rig whose projector stands above the camera its column alone puts points centimetres off.
DecodeParams decodeParamsFor(const ReconstructionParams& params, const io::RigCalibration& rig) {
  DecodeParams decode = params.decode;
  if (baselineAcrossColumns(rig) < kMinBaselineAcrossColumns) decode.keep_column_without_row = false;
  return decode;
}

// The white image, scaled, for every pixel: also where there is no point, as a camera image.
std::vector<float> intensitiesOf(const cv::Mat& intensity) {
  const cv::Mat continuous = intensity.isContinuous() ? intensity : intensity.clone();
  const auto* first = continuous.ptr<float>(0);
  return std::vector<float>(first, first + continuous.total());
}

// Without phase images a pixel is decoded to a whole code, code_step projector pixels wide: the
// depth that spans is the depth resolution the filters must allow between neighbours. With phase
// the coordinates are sub-pixel and the filters' fixed steps hold.
cv::Mat codeDepth(const DecodedCapture& decoded, const TriangulatedCloud& triangulated,
                  const io::PatternSetSpec& spec) {
  if (decoded.has_phase) return {};
  cv::Mat depth = triangulated.depth_per_projector_px * static_cast<double>(spec.code_step);
  if (decoded.stripe_run.empty()) return depth;
  // A pixel read along its stripe lies within half its run of codes, not half a code.
  depth.forEach<float>([&decoded](float& value, const int* at) {
    const uint8_t run = decoded.stripe_run.at<uint8_t>(at[0], at[1]);
    if (run > 2) value *= 0.5f * static_cast<float>(run);
  });
  return depth;
}

std::size_t pointsAlongStripes(const DecodedCapture& decoded, const cv::Mat& status) {
  if (decoded.stripe_run.empty()) return 0;
  cv::Mat along = (decoded.stripe_run > 0) & (status == static_cast<int>(PixelStatus::Valid));
  return static_cast<std::size_t>(cv::countNonZero(along));
}

const ReconstructionParams& validated(const ReconstructionParams& params) {
  params.validate();
  return params;
}

}  // namespace

void ReconstructionParams::setThreads(int threads) {
  decode.threads = threads;
  triangulation.threads = threads;
  filter.threads = threads;
}

void ReconstructionParams::validate() const {
  decode.validate();
  triangulation.validate();
  filter.validate();
}

Reconstructor::Reconstructor(const io::RigCalibration& rig, const ReconstructionParams& params)
    : params_(validated(params)), triangulator_(rig, params_.triangulation) {}

Reconstruction Reconstructor::reconstruct(const io::Capture& capture, const core::CancelFlag* cancel) const {
  requireCameraSize(capture, rig());
  requireProjectorSize(capture, rig());
  Reconstruction result;
  result.warnings = geometryWarnings(capture, rig());
  for (const std::string& warning : result.warnings) core::componentLogger("reconstruction")->warn(warning);
  core::Stopwatch stage;
  core::throwIfCancelled(cancel, "before decoding");
  const DecodedCapture decoded = decodeCapture(capture, decodeParamsFor(params_, rig()));
  result.timings.decode = stage.lapMs();
  core::throwIfCancelled(cancel, "before triangulation");
  TriangulatedCloud triangulated = triangulator_.triangulate(decoded);
  result.timings.triangulate = stage.lapMs();
  core::throwIfCancelled(cancel, "before filtering");
  triangulated.cloud.intensities = intensitiesOf(decoded.intensity);  // the noise filter reads them
  filterCloud(triangulated.cloud, triangulated.status, params_.filter,
              {decoded.column_noise, codeDepth(decoded, triangulated, capture.metadata.pattern_set)});
  result.timings.filter = stage.lapMs();
  // The three stages end to end; the copying into the result below is not part of it.
  result.timings.total = result.timings.decode + result.timings.triangulate + result.timings.filter;

  result.cloud = std::move(triangulated.cloud);
  result.status = triangulated.status;
  result.calibration_fit = triangulated.calibration_fit;
  result.counts = countStatuses(result.status);
  result.points_along_stripes = pointsAlongStripes(decoded, result.status);
  return result;
}

}  // namespace binpick::reconstruction
