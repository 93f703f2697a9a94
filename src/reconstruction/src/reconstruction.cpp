// Reconstructor: the stages in order, timed.
#include "binpick/reconstruction/reconstruction.hpp"

#include <string>

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

Reconstructor::Reconstructor(const io::RigCalibration& rig, const ReconstructionParams& params)
    : params_(validated(params)), triangulator_(rig, params_.triangulation) {}

Reconstruction Reconstructor::reconstruct(const io::Capture& capture, const core::CancelFlag* cancel) const {
  requireCameraSize(capture, rig());
  Reconstruction result;
  core::Stopwatch stage;
  core::throwIfCancelled(cancel, "before decoding");
  const DecodedCapture decoded = decodeCapture(capture, params_.decode);
  result.timings.decode = stage.lapMs();
  core::throwIfCancelled(cancel, "before triangulation");
  TriangulatedCloud triangulated = triangulator_.triangulate(decoded);
  result.timings.triangulate = stage.lapMs();
  core::throwIfCancelled(cancel, "before filtering");
  filterCloud(triangulated.cloud, triangulated.status, params_.filter);
  result.timings.filter = stage.lapMs();
  // The three stages end to end; the copying into the result below is not part of it.
  result.timings.total = result.timings.decode + result.timings.triangulate + result.timings.filter;

  result.cloud = std::move(triangulated.cloud);
  result.cloud.intensities = intensitiesOf(decoded.intensity);
  result.status = triangulated.status;
  result.counts = countStatuses(result.status);
  return result;
}

}  // namespace binpick::reconstruction
