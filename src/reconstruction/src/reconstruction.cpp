// Reconstructor: the stages in order, timed.
#include "binpick/reconstruction/reconstruction.hpp"

#include <chrono>
#include <string>

#include "binpick/io/error.hpp"

namespace binpick::reconstruction {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsBetween(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

void requireCameraSize(const Capture& capture, const RigCalibration& rig) {
  const CaptureMetadata& m = capture.metadata;
  if (m.image_width == rig.camera.width && m.image_height == rig.camera.height) return;
  throw Error("capture: images are " + std::to_string(m.image_width) + "x" + std::to_string(m.image_height) +
              " but the calibration's camera is " + std::to_string(rig.camera.width) + "x" +
              std::to_string(rig.camera.height));
}

// The white image, scaled, for every pixel: also where there is no point, as a camera image.
std::vector<float> intensitiesOf(const cv::Mat& intensity) {
  const cv::Mat continuous = intensity.isContinuous() ? intensity : intensity.clone();
  const auto* first = continuous.ptr<float>(0);
  return std::vector<float>(first, first + continuous.total());
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

Reconstructor::Reconstructor(const RigCalibration& rig, const ReconstructionParams& params)
    : params_(validated(params)), triangulator_(rig, params_.triangulation) {}

Reconstruction Reconstructor::reconstruct(const Capture& capture) const {
  requireCameraSize(capture, rig());
  const Clock::time_point start = Clock::now();
  const DecodedCapture decoded = decodeCapture(capture, params_.decode);
  const Clock::time_point decoded_at = Clock::now();
  TriangulatedCloud triangulated = triangulator_.triangulate(decoded);
  const Clock::time_point triangulated_at = Clock::now();
  filterCloud(triangulated.cloud, triangulated.status, params_.filter);
  const Clock::time_point filtered_at = Clock::now();

  Reconstruction result;
  result.cloud = std::move(triangulated.cloud);
  result.cloud.intensities = intensitiesOf(decoded.intensity);
  result.status = triangulated.status;
  result.counts = countStatuses(result.status);
  result.timings.decode = millisecondsBetween(start, decoded_at);
  result.timings.triangulate = millisecondsBetween(decoded_at, triangulated_at);
  result.timings.filter = millisecondsBetween(triangulated_at, filtered_at);
  result.timings.total = millisecondsBetween(start, filtered_at);
  return result;
}

}  // namespace binpick::reconstruction
