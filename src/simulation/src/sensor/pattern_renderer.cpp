// renderPatternImages: pattern-independent pixel lighting -> one camera image per pattern.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "normal_table.hpp"
#include "projector_blur.hpp"
#include "random.hpp"

namespace binpick::simulation {
namespace {

namespace rc = binpick::reconstruction;

constexpr uint32_t kImageNoiseStream = 2;

// A pattern as the projector emits it along its axis (black level included), and its mean.
struct EmittedPattern {
  rc::PatternAxis axis = rc::PatternAxis::None;
  std::vector<float> brightness;  // per projector column or row; one value for white/black
  float mean = 0.0f;
};

std::vector<EmittedPattern> emittedPatterns(const io::PatternSetSpec& spec, double black_level) {
  std::vector<EmittedPattern> emitted;
  for (const rc::Pattern& pattern : rc::patternSequence(spec)) {
    EmittedPattern e;
    e.axis = pattern.axis;
    const int size = e.axis == rc::PatternAxis::Columns ? spec.projector_width
                     : e.axis == rc::PatternAxis::Rows  ? spec.projector_height
                                                        : 1;
    double sum = 0.0;
    for (int i = 0; i < size; ++i) {
      const double b = rc::patternBrightness(pattern, spec, i);
      e.brightness.push_back(static_cast<float>(black_level + (1.0 - black_level) * b));
      sum += e.brightness.back();
    }
    e.mean = static_cast<float>(sum / size);
    emitted.push_back(std::move(e));
  }
  return emitted;
}

float blurred(const std::vector<float>& brightness, const detail::BlurTaps& taps) {
  float sum = 0.0f;
  for (int k = 0; k < taps.count; ++k) sum += taps.weight[k] * brightness[taps.first + k];
  return sum;
}

// The projector brightness that reaches the pixel's surface point under one pattern.
float incidentBrightness(const EmittedPattern& pattern, const detail::BlurTaps& column_taps,
                         const detail::BlurTaps& row_taps) {
  switch (pattern.axis) {
    case rc::PatternAxis::Columns: return blurred(pattern.brightness, column_taps);
    case rc::PatternAxis::Rows: return blurred(pattern.brightness, row_taps);
    case rc::PatternAxis::None: break;
  }
  return pattern.brightness.front();
}

// Counts the sensor reports: signal plus shot and read noise, quantised and saturated.
template <typename Pixel>
Pixel sensorValue(double signal, const PhotometryParams& params, double scale, double full_scale,
                  detail::SplitMix64& rng) {
  const double sigma = std::sqrt(params.read_noise * params.read_noise + params.shot_noise_gain * signal);
  const double noisy = (signal + sigma * detail::tabulatedStandardNormal(rng())) * scale;
  return static_cast<Pixel>(std::clamp(std::round(noisy), 0.0, full_scale));
}

template <typename Pixel>
void renderRows(const std::vector<PixelLighting>& pixels, int width, int height, const io::PatternSetSpec& spec,
                const PhotometryParams& params, const std::vector<EmittedPattern>& patterns,
                std::vector<cv::Mat>& images) {
  const double scale = params.bit_depth == 16 ? 257.0 : 1.0;
  const double full_scale = params.bit_depth == 16 ? 65535.0 : 255.0;
  const detail::KeyedStreams noise(params.seed, kImageNoiseStream);
  const uint64_t pixel_count = static_cast<uint64_t>(width) * height;
#pragma omp parallel for schedule(dynamic, 8) num_threads(core::resolveThreadCount(params.threads))
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const std::size_t index = static_cast<std::size_t>(row) * width + col;
      const PixelLighting& light = pixels[index];
      const detail::BlurTaps column_taps = detail::blurTaps(light.projector_x, light.blur_sigma, spec.projector_width);
      const detail::BlurTaps row_taps = detail::blurTaps(light.projector_y, light.blur_sigma, spec.projector_height);
      for (std::size_t p = 0; p < patterns.size(); ++p) {
        const double signal = light.ambient + light.global * patterns[p].mean +
                              light.direct * incidentBrightness(patterns[p], column_taps, row_taps);
        detail::SplitMix64 rng = noise.forItem(p * pixel_count + index);
        images[p].ptr<Pixel>(row)[col] = sensorValue<Pixel>(signal, params, scale, full_scale, rng);
      }
    }
  }
}

}  // namespace

namespace {

// The first `count` images of the pattern sequence (all of them when count exceeds it). Noise is
// keyed by pattern index, so a prefix renders exactly as it does within the whole set.
std::vector<cv::Mat> renderFirstPatterns(const std::vector<PixelLighting>& pixels, int width, int height,
                                         const io::PatternSetSpec& spec, const PhotometryParams& params,
                                         std::size_t count) {
  params.validate();
  spec.validate();
  if (width <= 0 || height <= 0 ||
      pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw core::Error("renderPatternImages: " + std::to_string(pixels.size()) + " pixels for a " +
                      std::to_string(width) + "x" + std::to_string(height) + " image");
  }
  std::vector<EmittedPattern> patterns = emittedPatterns(spec, params.projector_black_level);
  if (patterns.size() > count) patterns.resize(count);
  const int type = params.bit_depth == 16 ? CV_16UC1 : CV_8UC1;
  std::vector<cv::Mat> images;
  for (std::size_t p = 0; p < patterns.size(); ++p) images.emplace_back(height, width, type);
  if (params.bit_depth == 16) {
    renderRows<uint16_t>(pixels, width, height, spec, params, patterns, images);
  } else {
    renderRows<uint8_t>(pixels, width, height, spec, params, patterns, images);
  }
  return images;
}

}  // namespace

std::vector<cv::Mat> renderPatternImages(const std::vector<PixelLighting>& pixels, int width, int height,
                                         const io::PatternSetSpec& spec, const PhotometryParams& params) {
  return renderFirstPatterns(pixels, width, height, spec, params, SIZE_MAX);
}

cv::Mat renderWhiteImage(const std::vector<PixelLighting>& pixels, int width, int height,
                         const io::PatternSetSpec& spec, const PhotometryParams& params) {
  // Every pattern sequence starts with the white image (reconstruction::patternSequence).
  return renderFirstPatterns(pixels, width, height, spec, params, 1).front();
}

}  // namespace binpick::simulation

// PhotometryParams::validate: every field checked, the message names the first bad one.
namespace binpick::simulation {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "PhotometryParams", field, rule, value);
}

bool nonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void PhotometryParams::validate() const {
  require(nonNegative(projector_white), "projector_white", ">= 0", projector_white);
  require(positive(reference_distance), "reference_distance", "positive", reference_distance);
  require(nonNegative(projector_black_level) && projector_black_level < 1.0, "projector_black_level", "in [0, 1)",
          projector_black_level);
  require(nonNegative(ambient), "ambient", ">= 0", ambient);
  require(nonNegative(albedo_scale), "albedo_scale", ">= 0", albedo_scale);
  require(nonNegative(global_light) && global_light <= 1.0, "global_light", "in [0, 1]", global_light);
  require(nonNegative(specular), "specular", ">= 0", specular);
  require(positive(shininess), "shininess", "positive", shininess);
  require(positive(focus_distance), "focus_distance", "positive", focus_distance);
  require(nonNegative(defocus_per_dioptre), "defocus_per_dioptre", ">= 0", defocus_per_dioptre);
  require(nonNegative(min_blur_sigma), "min_blur_sigma", ">= 0", min_blur_sigma);
  require(nonNegative(read_noise), "read_noise", ">= 0", read_noise);
  require(nonNegative(shot_noise_gain), "shot_noise_gain", ">= 0", shot_noise_gain);
  require(bit_depth == 8 || bit_depth == 16, "bit_depth", "8 or 16", bit_depth);
  require(threads >= 0, "threads", ">= 0", threads);
}

}  // namespace binpick::simulation
