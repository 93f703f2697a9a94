// decodeCapture: checks, then every tile in parallel.
#include <algorithm>
#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/reconstruction/decoder.hpp"
#include "capture_completion.hpp"
#include "capture_layout.hpp"
#include "capture_light_check.hpp"
#include "capture_order_check.hpp"
#include "decode_plan.hpp"
#include "neighbour_unwrap.hpp"
#include "sensor_noise_estimate.hpp"
#include "stripe_reading.hpp"
#include "tile_decoder.hpp"

namespace binpick::reconstruction {
namespace {

DecodedCapture allocate(const detail::CaptureLayout& layout, bool column_noise) {
  DecodedCapture decoded;
  decoded.width = layout.width;
  decoded.height = layout.height;
  decoded.column.create(layout.height, layout.width, CV_32FC1);
  if (layout.rows.present) decoded.row.create(layout.height, layout.width, CV_32FC1);
  decoded.status.create(layout.height, layout.width, CV_8UC1);
  if (column_noise) decoded.column_noise.create(layout.height, layout.width, CV_32FC1);
  decoded.intensity.create(layout.height, layout.width, CV_32FC1);
  decoded.has_phase = layout.columns.hasPhase();
  return decoded;
}

detail::TileOutput outputOf(DecodedCapture& decoded) {
  detail::TileOutput out;
  out.column_noise = decoded.column_noise.empty() ? nullptr : decoded.column_noise.ptr<float>(0);
  out.column = decoded.column.ptr<float>(0);
  out.row = decoded.row.empty() ? nullptr : decoded.row.ptr<float>(0);
  out.status = decoded.status.ptr<uint8_t>(0);
  out.intensity = decoded.intensity.ptr<float>(0);
  return out;
}

// The tile loops run over consecutive pixels across rows: every image must be one block.
io::Capture withContinuousImages(const io::Capture& capture) {
  io::Capture continuous = capture;
  for (cv::Mat& image : continuous.images) {
    if (!image.isContinuous()) image = image.clone();
  }
  return continuous;
}

// Tiles are independent: the result does not depend on the thread count. Returns the pixels whose
// Gray code was too uncertain, for unwrapFromNeighbours (when `collect_candidates`), in no
// particular order.
template <typename Pixel>
std::vector<detail::UnwrapCandidate> decodeTiles(const io::Capture& capture, const detail::DecodePlan& plan,
                                                 int threads, bool collect_candidates, DecodedCapture& decoded) {
  const std::size_t pixels = static_cast<std::size_t>(plan.layout.width) * static_cast<std::size_t>(plan.layout.height);
  const auto tiles = static_cast<long>((pixels + detail::kTilePixels - 1) / detail::kTilePixels);
  std::vector<detail::UnwrapCandidate> candidates;
#pragma omp parallel num_threads(threads)
  {
    detail::TileScratch<detail::WorkType<Pixel>> scratch;
    std::vector<detail::UnwrapCandidate> found;
    detail::TileOutput out = outputOf(decoded);
    if (collect_candidates) out.candidates = &found;
#pragma omp for schedule(static, 4)
    for (long tile = 0; tile < tiles; ++tile) {
      const std::size_t offset = static_cast<std::size_t>(tile) * detail::kTilePixels;
      const int count = static_cast<int>(std::min<std::size_t>(detail::kTilePixels, pixels - offset));
      detail::decodeTile<Pixel>(capture, plan, offset, count, scratch, out);
    }
#pragma omp critical(binpick_unwrap_candidates)
    candidates.insert(candidates.end(), found.begin(), found.end());
  }
  return candidates;
}

// The bit margin's noise term: k^2 var(p - q) = k^2 (2 read + gain (p + q)), with p + q = white +
// black.
void capMarginsByNoise(const detail::SensorNoise& noise, double sigmas, detail::DecodeThresholds& t) {
  const auto k2 = static_cast<float>(sigmas * sigmas);
  t.noise_floor = k2 * 2.0f * noise.read;
  t.noise_slope = k2 * noise.gain;
}

// The column's noise from N phase steps I_k = A + B cos(phi - 2 pi k / N), each with variance
// read + gain A, A = (white + black) / 2: var(phi) = 2 var(I) / (N B^2), times (period / 2 pi)^2.
void setColumnNoiseModel(const detail::SensorNoise& noise, const detail::AxisLayout& columns,
                         detail::DecodeThresholds& t) {
  const double steps = static_cast<double>(columns.phase_images.size());
  const double to_pixels = columns.phase_period / (2.0 * M_PI);
  const double scale2 = 2.0 / steps * to_pixels * to_pixels;
  t.column_noise_read = static_cast<float>(scale2 * noise.read);
  t.column_noise_gain = static_cast<float>(scale2 * noise.gain * 0.5);
}

// Codes to projector pixels (PatternSetSpec::code_step): the centre of each code's block.
void scaleToProjectorPixels(DecodedCapture& decoded, int code_step) {
  if (code_step == 1) return;
  for (cv::Mat* coordinates : {&decoded.column, &decoded.row}) {
    if (coordinates->empty()) continue;
    coordinates->forEach<float>([code_step](float& value, const int*) {
      value = detail::projectorPixelOfCode(value, code_step);  // NaN stays NaN
    });
  }
  if (!decoded.column_noise.empty()) decoded.column_noise *= code_step;
}

}  // namespace

DecodedCapture decodeCapture(const io::Capture& original, const DecodeParams& params) {
  params.validate();
  const detail::CompleteCapture complete = detail::completeCapture(original);
  const io::Capture& capture = complete.capture;
  detail::DecodePlan plan = detail::makeDecodePlan(detail::captureLayout(capture), params);
  detail::checkCaptureLight(capture, plan, params);
  detail::checkCaptureOrder(capture, plan);
  const bool has_phase = plan.layout.columns.hasPhase();
  detail::SensorNoise noise;
  if (params.bit_noise_sigmas > 0.0 || has_phase) {
    noise = detail::estimateSensorNoise(capture, plan.layout, plan.thresholds.saturation, plan.thresholds.min_contrast);
  }
  if (noise.measured && params.bit_noise_sigmas > 0.0)
    capMarginsByNoise(noise, params.bit_noise_sigmas, plan.thresholds);
  if (noise.measured && has_phase) setColumnNoiseModel(noise, plan.layout.columns, plan.thresholds);
  DecodedCapture decoded = allocate(plan.layout, noise.measured && has_phase);
  const int threads = core::resolveThreadCount(params.threads);
  const io::Capture continuous = withContinuousImages(capture);
  const bool unwrap = params.min_unwrap_neighbours > 0 && has_phase;
  const std::vector<detail::UnwrapCandidate> candidates =
      plan.layout.bit_depth == 8 ? decodeTiles<uint8_t>(continuous, plan, threads, unwrap, decoded)
                                 : decodeTiles<uint16_t>(continuous, plan, threads, unwrap, decoded);
  if (unwrap) detail::unwrapFromNeighbours(candidates, plan, params.min_unwrap_neighbours, threads, decoded);
  detail::readAlongStripes(continuous, plan, params, threads, decoded);
  scaleToProjectorPixels(decoded, complete.code_step);
  decoded.code_step = complete.code_step;
  return decoded;
}

}  // namespace binpick::reconstruction

// DecodeParams::validate.
namespace binpick::reconstruction {
namespace {

bool nonNegative(double value) { return std::isfinite(value) && value >= 0.0; }

}  // namespace

void DecodeParams::validate() const {
  const std::string owner = "decode params";
  core::requireField(nonNegative(min_contrast), owner, "min_contrast", "finite and >= 0", min_contrast);
  core::requireField(nonNegative(min_direct), owner, "min_direct", "finite and >= 0", min_direct);
  core::requireField(
      std::isfinite(projector_black_level) && projector_black_level >= 0.0 && projector_black_level < 0.5, owner,
      "projector_black_level", "in [0, 0.5)", projector_black_level);
  core::requireField(separation_min_stripe >= 1, owner, "separation_min_stripe", ">= 1", separation_min_stripe);
  core::requireField(separation_max_stripe >= separation_min_stripe, owner, "separation_max_stripe",
                     ">= separation_min_stripe", separation_max_stripe);
  core::requireField(nonNegative(min_bit_difference), owner, "min_bit_difference", "finite and >= 0",
                     min_bit_difference);
  core::requireField(std::isfinite(bit_margin) && bit_margin >= 0.0 && bit_margin < 1.0, owner, "bit_margin",
                     "in [0, 1)", bit_margin);
  core::requireField(std::isfinite(bit_noise_sigmas) && bit_noise_sigmas >= 0.0 && bit_noise_sigmas <= 10.0, owner,
                     "bit_noise_sigmas", "in [0, 10]", bit_noise_sigmas);
  core::requireField(max_code_run_without_phase >= 1 && max_code_run_without_phase <= 64, owner,
                     "max_code_run_without_phase", "in [1, 64]", max_code_run_without_phase);
  core::requireField(max_code_run_with_phase >= 1 && max_code_run_with_phase <= 64, owner, "max_code_run_with_phase",
                     "in [1, 64]", max_code_run_with_phase);
  core::requireField(nonNegative(min_phase_amplitude), owner, "min_phase_amplitude", "finite and >= 0",
                     min_phase_amplitude);
  core::requireField(nonNegative(max_phase_gray_disagreement), owner, "max_phase_gray_disagreement", "finite and >= 0",
                     max_phase_gray_disagreement);
  core::requireField(
      std::isfinite(max_saturated_fraction) && max_saturated_fraction >= 0.0 && max_saturated_fraction <= 1.0, owner,
      "max_saturated_fraction", "in [0, 1]", max_saturated_fraction);
  core::requireField(std::isfinite(max_pair_sum_error) && max_pair_sum_error > 0.0, owner, "max_pair_sum_error",
                     "positive", max_pair_sum_error);
  core::requireField(min_unwrap_neighbours >= 0 && min_unwrap_neighbours <= 8, owner, "min_unwrap_neighbours",
                     "in [0, 8]", min_unwrap_neighbours);
  core::requireField(stripe_reach >= 0 && stripe_reach <= 64, owner, "stripe_reach", "in [0, 64]", stripe_reach);
  core::requireField(max_code_run_along_stripe >= 1 && max_code_run_along_stripe <= 64, owner,
                     "max_code_run_along_stripe", "in [1, 64]", max_code_run_along_stripe);
  core::requireField(threads >= 0, owner, "threads", ">= 0", threads);
}

}  // namespace binpick::reconstruction
