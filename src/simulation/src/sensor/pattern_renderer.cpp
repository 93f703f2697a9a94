// renderPatternImages: pattern-independent pixel lighting -> one camera image per pattern.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

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

// One surface point a pixel sees, with the projector pixels its defocus spreads over.
struct LitPoint {
  const PixelLighting* light = nullptr;
  detail::BlurTaps column_taps, row_taps;
};

LitPoint litPoint(const PixelLighting& light, const io::PatternSetSpec& spec) {
  return {&light, detail::blurTaps(light.projector_x, light.blur_sigma, spec.projector_width),
          detail::blurTaps(light.projector_y, light.blur_sigma, spec.projector_height)};
}

// The counts the point sends to the pixel under one pattern, before noise.
double signalOf(const LitPoint& point, const EmittedPattern& pattern) {
  const PixelLighting& light = *point.light;
  return light.ambient + light.global * pattern.mean +
         light.direct * incidentBrightness(pattern, point.column_taps, point.row_taps);
}

// The signal of a mixed pixel: the light of each surface it sees, by its share.
double mixedSignalOf(const std::vector<LitPoint>& surfaces, const std::vector<float>& shares,
                     const EmittedPattern& pattern) {
  double sum = 0.0;
  for (std::size_t k = 0; k < surfaces.size(); ++k) sum += shares[k] * signalOf(surfaces[k], pattern);
  return sum;
}

void requireMixedPixelLayout(const MixedPixels& mixed) {
  const bool partition = mixed.first.size() == mixed.pixel.size() + 1 && mixed.first.front() == 0 &&
                         mixed.first.back() == mixed.surfaces.size() &&
                         std::is_sorted(mixed.first.begin(), mixed.first.end());
  if (!partition) {
    throw core::Error("renderPatternImages: the mixed pixels' `first` (" + std::to_string(mixed.first.size()) +
                      " entries) does not split their " + std::to_string(mixed.surfaces.size()) +
                      " surfaces among " + std::to_string(mixed.pixel.size()) + " pixels");
  }
  for (const SeenSurface& surface : mixed.surfaces) {
    if (!(surface.share >= 0.0f && surface.share <= 1.0f)) {
      throw core::Error("renderPatternImages: a mixed pixel's surface has share " + std::to_string(surface.share) +
                        ", not in [0, 1]");
    }
  }
}

// For each image pixel, the index of its entry in MixedPixels::pixel, or -1 (empty when there
// are no mixed pixels). Throws on a bad layout, a pixel outside the image or a repeated one.
std::vector<int32_t> mixedSlots(const MixedPixels& mixed, std::size_t pixel_count) {
  std::vector<int32_t> slot;
  if (mixed.pixel.empty() && mixed.first.size() <= 1 && mixed.surfaces.empty()) return slot;
  requireMixedPixelLayout(mixed);
  slot.assign(pixel_count, -1);
  for (std::size_t m = 0; m < mixed.pixel.size(); ++m) {
    const std::size_t i = mixed.pixel[m];
    if (i >= pixel_count || slot[i] >= 0) {
      throw core::Error("renderPatternImages: mixed pixel " + std::to_string(i) +
                        (i >= pixel_count ? " is outside the image" : " is listed twice"));
    }
    slot[i] = static_cast<int32_t>(m);
  }
  return slot;
}

template <typename Pixel>
void renderRows(const std::vector<PixelLighting>& pixels, int width, int height, const io::PatternSetSpec& spec,
                const PhotometryParams& params, const MixedPixels& mixed, const std::vector<int32_t>& mixed_slot,
                const std::vector<EmittedPattern>& patterns, std::vector<cv::Mat>& images) {
  const double scale = params.bit_depth == 16 ? 257.0 : 1.0;
  const double full_scale = params.bit_depth == 16 ? 65535.0 : 255.0;
  const detail::KeyedStreams noise(params.seed, kImageNoiseStream);
  const uint64_t pixel_count = static_cast<uint64_t>(width) * height;
#pragma omp parallel for schedule(dynamic, 8) num_threads(core::resolveThreadCount(params.threads))
  for (int row = 0; row < height; ++row) {
    std::vector<LitPoint> surfaces;  // a mixed pixel's
    std::vector<float> shares;
    for (int col = 0; col < width; ++col) {
      const std::size_t index = static_cast<std::size_t>(row) * width + col;
      const int32_t slot = mixed_slot.empty() ? -1 : mixed_slot[index];
      const LitPoint centre = litPoint(pixels[index], spec);
      surfaces.clear();
      shares.clear();
      if (slot >= 0) {
        for (std::size_t k = mixed.first[slot]; k < mixed.first[slot + 1]; ++k) {
          surfaces.push_back(litPoint(mixed.surfaces[k].light, spec));
          shares.push_back(mixed.surfaces[k].share);
        }
      }
      for (std::size_t p = 0; p < patterns.size(); ++p) {
        const double signal =
            slot >= 0 ? mixedSignalOf(surfaces, shares, patterns[p]) : signalOf(centre, patterns[p]);
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
                                         const MixedPixels& mixed, std::size_t count) {
  params.validate();
  spec.validate();
  if (width <= 0 || height <= 0 ||
      pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw core::Error("renderPatternImages: " + std::to_string(pixels.size()) + " pixels for a " +
                      std::to_string(width) + "x" + std::to_string(height) + " image");
  }
  const std::vector<int32_t> mixed_slot = mixedSlots(mixed, pixels.size());
  std::vector<EmittedPattern> patterns = emittedPatterns(spec, params.projector_black_level);
  if (patterns.size() > count) patterns.resize(count);
  const int type = params.bit_depth == 16 ? CV_16UC1 : CV_8UC1;
  std::vector<cv::Mat> images;
  for (std::size_t p = 0; p < patterns.size(); ++p) images.emplace_back(height, width, type);
  if (params.bit_depth == 16) {
    renderRows<uint16_t>(pixels, width, height, spec, params, mixed, mixed_slot, patterns, images);
  } else {
    renderRows<uint8_t>(pixels, width, height, spec, params, mixed, mixed_slot, patterns, images);
  }
  return images;
}

}  // namespace

std::vector<cv::Mat> renderPatternImages(const std::vector<PixelLighting>& pixels, int width, int height,
                                         const io::PatternSetSpec& spec, const PhotometryParams& params,
                                         const MixedPixels& mixed) {
  return renderFirstPatterns(pixels, width, height, spec, params, mixed, SIZE_MAX);
}

cv::Mat renderWhiteImage(const std::vector<PixelLighting>& pixels, int width, int height,
                         const io::PatternSetSpec& spec, const PhotometryParams& params) {
  // Every pattern sequence starts with the white image (reconstruction::patternSequence).
  return renderFirstPatterns(pixels, width, height, spec, params, MixedPixels{}, 1).front();
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

// 256 rays per edge pixel: beyond that the mean light no longer changes, only the cost grows.
constexpr int kMaxMixedPixelSamples = 16;
// A blur wider than this is a lens far out of focus; the edge pixels traced would grow with it.
constexpr double kMaxCameraBlurSigma = 3.0;

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
  require(mixed_pixel_samples >= 1 && mixed_pixel_samples <= kMaxMixedPixelSamples, "mixed_pixel_samples",
          "in [1, 16]", mixed_pixel_samples);
  require(nonNegative(camera_blur_sigma) && camera_blur_sigma <= kMaxCameraBlurSigma, "camera_blur_sigma",
          "in [0, 3] pixels", camera_blur_sigma);
  require(threads >= 0, "threads", ">= 0", threads);
}

}  // namespace binpick::simulation
