// Rendered captures, cached per options.
#include "virtual_capture.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "binpick/simulation/parts.hpp"
#include "sensor/lighting_presets.hpp"

namespace binpick::reconstruction::testing {

namespace {

// NaN (no override) compares equal to NaN here, so that options are ordered.
double key(double value) { return std::isnan(value) ? -1e300 : value; }

}  // namespace

bool CaptureOptions::operator<(const CaptureOptions& o) const {
  return std::make_tuple(part, objects, seed, camera_scale, bin_length, bin_width, row_codes, phase_steps, bit_depth,
                         lighting, key(global_light), key(ambient), key(projector_blur), mixed_pixel_samples, code_step,
                         phase_period, gray_unit) <
         std::make_tuple(o.part, o.objects, o.seed, o.camera_scale, o.bin_length, o.bin_width, o.row_codes,
                         o.phase_steps, o.bit_depth, o.lighting, key(o.global_light), key(o.ambient),
                         key(o.projector_blur), o.mixed_pixel_samples, o.code_step, o.phase_period, o.gray_unit);
}

namespace {

VirtualCapture render(const CaptureOptions& options) {
  VirtualCapture v;
  v.params.objects = options.objects;
  v.params.seed = options.seed;
  v.params.rig.camera = v.params.rig.camera.scaled(options.camera_scale);
  v.params.bin_length = options.bin_length;
  v.params.bin_width = options.bin_width;
  io::PatternSetSpec patterns;
  patterns.projector_width = v.params.rig.projector.width;
  patterns.projector_height = v.params.rig.projector.height;
  patterns.row_codes = options.row_codes;
  patterns.phase_steps = options.phase_steps;
  patterns.code_step = options.code_step;
  patterns.phase_period = options.phase_period * options.code_step;  // the same period in codes
  patterns.gray_unit = options.gray_unit * options.code_step;
  simulation::PhotometryParams photometry = simulation::photometryPreset(options.lighting);
  photometry.seed = options.seed;
  photometry.bit_depth = options.bit_depth;
  if (!std::isnan(options.global_light)) photometry.global_light = options.global_light;
  if (!std::isnan(options.ambient)) photometry.ambient = options.ambient;
  if (!std::isnan(options.projector_blur)) photometry.min_blur_sigma = options.projector_blur;
  photometry.mixed_pixel_samples = options.mixed_pixel_samples;
  simulation::PileCapture pile =
      simulation::generatePileCapture(simulation::makePart(options.part).mesh, v.params, patterns, photometry);
  v.scene = std::move(pile.scene);
  v.capture = simulation::recordedCapture(std::move(pile.images), v.params, patterns, photometry, "test");
  return v;
}

}  // namespace

Eigen::Vector2d VirtualCapture::trueProjectorPixel(std::size_t pixel) const {
  const Eigen::Vector3f point = scene.exact_cloud.points[pixel];
  if (!point.allFinite()) return Eigen::Vector2d::Constant(std::nan(""));
  return scene.rig.projector.project(scene.rig.T_projector_camera * point.cast<double>());
}

bool VirtualCapture::measurable(std::size_t pixel) const { return scene.cloud.points[pixel].allFinite(); }

bool VirtualCapture::inShadow(std::size_t pixel) const {
  // Seen but not measured by the ideal sensor: unlit, or seen too obliquely (beyond 80 degrees).
  const Eigen::Vector3f point = scene.exact_cloud.points[pixel];
  const Eigen::Vector3f normal = scene.exact_cloud.normals[pixel];
  if (!point.allFinite() || measurable(pixel)) return false;
  return -normal.dot(point.normalized()) > 0.3f;  // not grazing: the projector's light is what is missing
}

const VirtualCapture& virtualCapture(const CaptureOptions& options) {
  static std::mutex mutex;
  static std::map<CaptureOptions, VirtualCapture> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto found = cache.find(options);
  if (found == cache.end()) found = cache.emplace(options, render(options)).first;
  return found->second;
}

io::Capture deepCopy(const io::Capture& capture) {
  io::Capture copy = capture;
  for (cv::Mat& image : copy.images) image = image.clone();
  return copy;
}

}  // namespace binpick::reconstruction::testing
