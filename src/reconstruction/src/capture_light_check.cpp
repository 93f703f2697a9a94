// Capture-level photometric checks: a capture with the projector off, an overexposed one, or one
// with a lost, black or shuffled frame is refused with a message, rather than decoded into a
// cloud full of holes or, worse, wrong points.
#include "capture_light_check.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"

namespace binpick::reconstruction::detail {
namespace {

constexpr int kSampleStep = 8;           // every 8th pixel of every 8th row
constexpr std::size_t kMinSamples = 50;  // fewer well-lit samples: too little evidence to refuse

struct PixelSample {
  int x = 0;
  int y = 0;
  float white = 0.0f;
  float black = 0.0f;
};

template <typename Pixel>
float valueAt(const io::Capture& capture, int image, const PixelSample& at) {
  return static_cast<float>(capture.images[static_cast<std::size_t>(image)].at<Pixel>(at.y, at.x));
}

template <typename Pixel>
std::vector<PixelSample> samplePixels(const io::Capture& capture, const CaptureLayout& layout) {
  std::vector<PixelSample> samples;
  for (int y = kSampleStep / 2; y < layout.height; y += kSampleStep) {
    for (int x = kSampleStep / 2; x < layout.width; x += kSampleStep) {
      PixelSample s{x, y, 0.0f, 0.0f};
      s.white = valueAt<Pixel>(capture, layout.white, s);
      s.black = valueAt<Pixel>(capture, layout.black, s);
      samples.push_back(s);
    }
  }
  return samples;
}

std::string imageName(const io::Capture& capture, int image) {
  return std::to_string(image) + " (" + capture.metadata.patterns[static_cast<std::size_t>(image)] + ")";
}

std::string percent(double fraction) {
  char text[16];
  std::snprintf(text, sizeof text, "%.0f%%", 100.0 * fraction);
  return text;
}

std::string decimal(double value) {
  char text[24];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

// Returns the well-lit, unclipped samples that the frame checks may rely on.
std::vector<PixelSample> checkExposure(const io::Capture& capture, const std::vector<PixelSample>& samples,
                                       const DecodePlan& plan, const DecodeParams& params) {
  const DecodeThresholds& t = plan.thresholds;
  std::size_t lit = 0;
  std::size_t clipped = 0;
  std::vector<PixelSample> strong;
  for (const PixelSample& s : samples) {
    if (s.white - s.black < t.min_contrast) continue;
    ++lit;
    if (s.white >= t.saturation)
      ++clipped;
    else if (s.white - s.black >= 4.0f * t.min_contrast)
      strong.push_back(s);
  }
  if (lit == 0) {
    throw core::Error("capture: the white image " + imageName(capture, plan.layout.white) +
                      " is nowhere brighter than the black one by min_contrast (" + decimal(params.min_contrast) +
                      " counts): the projector did not light the scene, or the exposure is far too short");
  }
  const double clipped_fraction = static_cast<double>(clipped) / static_cast<double>(lit);
  if (clipped_fraction > params.max_saturated_fraction) {
    throw core::Error("capture: the white image is saturated on " + percent(clipped_fraction) +
                      " of the lit pixels (max_saturated_fraction " + percent(params.max_saturated_fraction) +
                      "): shorten the exposure or lower the gain");
  }
  return strong;
}

// A pattern and its inverse add up to white + black wherever the pixel sees the projector; a
// lost, black or shuffled frame breaks that on most pixels.
template <typename Pixel>
void checkPair(const io::Capture& capture, const std::vector<PixelSample>& strong, int pattern, int inverse,
               const DecodeParams& params) {
  double deviation = 0.0;
  for (const PixelSample& s : strong) {
    const float sum = valueAt<Pixel>(capture, pattern, s) + valueAt<Pixel>(capture, inverse, s);
    deviation += std::fabs((sum - 2.0f * s.black) / (s.white - s.black) - 1.0f);
  }
  deviation /= static_cast<double>(strong.size());
  if (deviation <= params.max_pair_sum_error) return;
  throw core::Error("capture: images " + imageName(capture, pattern) + " and " + imageName(capture, inverse) +
                    " do not add up to white + black (mean deviation " + decimal(deviation) +
                    " of white - black, max_pair_sum_error " + decimal(params.max_pair_sum_error) +
                    "): a frame is missing, black or out of order");
}

// Over many pixels (many phases), every phase step averages to half of white above black; a
// lost or black frame does not.
template <typename Pixel>
void checkPhaseStep(const io::Capture& capture, const std::vector<PixelSample>& strong, int image,
                    const DecodeParams& params) {
  double share = 0.0;
  for (const PixelSample& s : strong) {
    share += (valueAt<Pixel>(capture, image, s) - s.black) / (s.white - s.black);
  }
  const double deviation = std::fabs(2.0 * share / static_cast<double>(strong.size()) - 1.0);
  if (deviation <= params.max_pair_sum_error) return;
  throw core::Error("capture: phase image " + imageName(capture, image) +
                    " does not average to half of white above black (deviation " + decimal(deviation) +
                    ", max_pair_sum_error " + decimal(params.max_pair_sum_error) +
                    "): a frame is missing, black or out of order");
}

template <typename Pixel>
void checkFrames(const io::Capture& capture, const std::vector<PixelSample>& strong, const AxisLayout& axis,
                 const DecodeParams& params) {
  if (!axis.present) return;
  for (int bit = 0; bit < axis.bits(); ++bit) {
    checkPair<Pixel>(capture, strong, axis.bit_images[bit], axis.inverse_images[bit], params);
  }
  for (int image : axis.phase_images) checkPhaseStep<Pixel>(capture, strong, image, params);
}

template <typename Pixel>
void checkAll(const io::Capture& capture, const DecodePlan& plan, const DecodeParams& params) {
  const std::vector<PixelSample> samples = samplePixels<Pixel>(capture, plan.layout);
  const std::vector<PixelSample> strong = checkExposure(capture, samples, plan, params);
  if (strong.size() < kMinSamples) return;
  checkFrames<Pixel>(capture, strong, plan.layout.columns, params);
  checkFrames<Pixel>(capture, strong, plan.layout.rows, params);
}

}  // namespace

void checkCaptureLight(const io::Capture& capture, const DecodePlan& plan, const DecodeParams& params) {
  if (plan.layout.bit_depth == 8) {
    checkAll<uint8_t>(capture, plan, params);
  } else {
    checkAll<uint16_t>(capture, plan, params);
  }
}

}  // namespace binpick::reconstruction::detail
