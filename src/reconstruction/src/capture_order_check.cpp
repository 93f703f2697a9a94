// Capture-level order check: the phase of a well-lit pixel and its Gray code name the same
// projector column (row) to within a fraction of a period. Swapping a Gray pattern with its
// inverse reflects the decoded column within that bit's stripe block; swapping two phase steps
// changes the measured phase (for four steps, steps 1 and 3 negate it). Either way the two
// disagree on most pixels, and undoing the swap makes them agree again: that names the culprit.
#include "capture_order_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction::detail {
namespace {

constexpr int kSampleStep = 8;           // every 8th pixel of every 8th row, as the light check
constexpr std::size_t kMinSamples = 50;  // fewer usable samples: too little evidence to refuse
constexpr float kStrongContrast = 4.0f;  // white - black >= this many min_contrast
constexpr float kCertainBit = 0.15f;     // |pattern - inverse| >= this share of white - black
constexpr float kMinPhaseShare = 0.1f;   // sinusoid amplitude >= this share of white - black
// The declared order passes when the phase agrees with the Gray code on this share of the
// samples (clean and harsh virtual captures: over 0.9). A swap is named only when undoing it
// makes at least kExplained agree, and kGain more than the declared order.
constexpr double kAgreeing = 0.5;
constexpr double kExplained = 0.75;
constexpr double kGain = 0.3;

// Per sampled pixel: its Gray code (certain bits only) and its phase-step values above black.
struct AxisSamples {
  int steps = 0;
  std::vector<double> shifts;  // theta of each phase step (phaseShift, pattern_set.hpp)
  std::vector<unsigned> codes;
  std::vector<float> values;  // steps per sample
  // Samples next to each other on the sampling grid (right and below), as index pairs.
  std::vector<std::pair<std::size_t, std::size_t>> neighbours;
  std::size_t size() const { return codes.size(); }
};

// How well one reading of the images explains them: the share of samples whose phase agrees
// with their Gray code, and the share of neighbouring samples whose decoded columns jump apart.
struct Fit {
  double agreement = 0.0;
  double jumps = 0.0;
};
// A reflected Gray bit and a reversed phase both agree with the phase modulo a period, and so
// does undoing the wrong one of two coarse bits (two reflections are a shift by whole periods):
// the right reading also leaves the columns continuous between neighbours.

template <typename Pixel>
float valueAt(const io::Capture& capture, int image, int x, int y) {
  return static_cast<float>(capture.images[static_cast<std::size_t>(image)].at<Pixel>(y, x));
}

template <typename Pixel>
bool readCode(const io::Capture& capture, const AxisLayout& axis, int x, int y, float contrast, unsigned& code) {
  code = 0;
  for (int bit = 0; bit < axis.bits(); ++bit) {
    const float difference =
        valueAt<Pixel>(capture, axis.bit_images[bit], x, y) - valueAt<Pixel>(capture, axis.inverse_images[bit], x, y);
    if (std::fabs(difference) < kCertainBit * contrast) return false;
    code = (code << 1) | (difference > 0.0f ? 1u : 0u);
  }
  return true;
}

// The phase of `steps` values when the image at slot k shows step order[k] (of shift
// shifts[order[k]]).
float phaseOffset(const float* values, const std::vector<int>& order, const std::vector<double>& shifts, int period,
                  float* amplitude = nullptr) {
  const int steps = static_cast<int>(order.size());
  double sine = 0.0, cosine = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double shift = shifts[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    sine += values[k] * std::sin(shift);
    cosine += values[k] * std::cos(shift);
  }
  if (amplitude != nullptr) *amplitude = static_cast<float>(2.0 / steps * std::hypot(sine, cosine));
  return static_cast<float>(std::atan2(sine, cosine) * period / (2.0 * M_PI));
}

std::vector<int> declaredOrder(int steps) {
  std::vector<int> order(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) order[static_cast<std::size_t>(k)] = k;
  return order;
}

template <typename Pixel>
AxisSamples sampleAxis(const io::Capture& capture, const DecodePlan& plan, const AxisLayout& axis) {
  const CaptureLayout& layout = plan.layout;
  const DecodeThresholds& t = plan.thresholds;
  AxisSamples samples;
  samples.steps = static_cast<int>(axis.phase_images.size());
  for (int k = 0; k < samples.steps; ++k) samples.shifts.push_back(phaseShift(layout.pattern_set, k));
  const std::vector<int> order = declaredOrder(samples.steps);
  std::vector<float> values(static_cast<std::size_t>(samples.steps));
  const int grid_width = (layout.width + kSampleStep / 2) / kSampleStep;
  std::vector<long> previous_row(static_cast<std::size_t>(grid_width), -1);  // sample index, or -1
  for (int y = kSampleStep / 2; y < layout.height; y += kSampleStep) {
    std::vector<long> row(static_cast<std::size_t>(grid_width), -1);
    for (int x = kSampleStep / 2; x < layout.width; x += kSampleStep) {
      const float white = valueAt<Pixel>(capture, layout.white, x, y);
      const float black = valueAt<Pixel>(capture, layout.black, x, y);
      const float contrast = white - black;
      if (contrast < kStrongContrast * t.min_contrast || white >= t.saturation) continue;
      unsigned code = 0;
      if (!readCode<Pixel>(capture, axis, x, y, contrast, code)) continue;
      bool clipped = false;
      for (int k = 0; k < samples.steps; ++k) {
        const float value = valueAt<Pixel>(capture, axis.phase_images[static_cast<std::size_t>(k)], x, y);
        clipped = clipped || value >= t.saturation;
        values[static_cast<std::size_t>(k)] = value - black;
      }
      float amplitude = 0.0f;
      phaseOffset(values.data(), order, samples.shifts, axis.phase_period, &amplitude);
      if (clipped || amplitude < kMinPhaseShare * contrast) continue;
      const auto cell = static_cast<std::size_t>(x / kSampleStep);
      const std::size_t index = samples.codes.size();
      row[cell] = static_cast<long>(index);
      if (cell > 0 && row[cell - 1] >= 0)
        samples.neighbours.emplace_back(static_cast<std::size_t>(row[cell - 1]), index);
      if (previous_row[cell] >= 0) samples.neighbours.emplace_back(static_cast<std::size_t>(previous_row[cell]), index);
      samples.codes.push_back(code);
      samples.values.insert(samples.values.end(), values.begin(), values.end());
    }
    previous_row = std::move(row);
  }
  return samples;
}

// The fit of reading the samples' phase with `order` and their Gray code with the bits of `flip`
// inverted. Agreeing: the phase lands within an eighth of a period of the decoded column. A jump:
// neighbouring samples (8 camera pixels apart) decoded more than 1.5 periods apart, where the
// stripe blocks of a wrongly inverted bit meet.
Fit fit(const AxisSamples& samples, const AxisLayout& axis, const std::vector<int>& order, unsigned flip) {
  const float period = static_cast<float>(axis.phase_period);
  // A word of several columns (AxisLayout::gray_unit) places the phase anywhere inside it.
  const float half_word = 0.5f * static_cast<float>(axis.gray_unit - 1);
  const float tolerance = std::max(1.5f, period / 8.0f) + half_word;
  std::vector<long> columns(samples.size());
  std::size_t agreeing = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const unsigned column = grayDecode(samples.codes[i] ^ flip) * static_cast<unsigned>(axis.gray_unit);
    columns[i] = column < static_cast<unsigned>(axis.size) ? static_cast<long>(column) : -1;
    if (columns[i] < 0) continue;
    const float offset = phaseOffset(&samples.values[i * static_cast<std::size_t>(samples.steps)], order,
                                     samples.shifts, axis.phase_period);
    float residual = offset - (static_cast<float>(column) + half_word);
    residual -= period * std::round(residual / period);
    if (std::fabs(residual) <= tolerance) ++agreeing;
  }
  std::size_t pairs = 0, jumps = 0;
  for (const auto& [a, b] : samples.neighbours) {
    if (columns[a] < 0 || columns[b] < 0) continue;
    ++pairs;
    if (static_cast<float>(std::labs(columns[a] - columns[b])) > 1.5f * period) ++jumps;
  }
  Fit result;
  result.agreement = static_cast<double>(agreeing) / static_cast<double>(samples.size());
  result.jumps = pairs == 0 ? 0.0 : static_cast<double>(jumps) / static_cast<double>(pairs);
  return result;
}

// The name of image `index` as stored: its file name without the extension, e.g.
// "012_gray_col_03".
std::string imageLabel(const io::Capture& capture, int index) {
  const auto i = static_cast<std::size_t>(index);
  if (i < capture.metadata.images.size()) {
    return std::filesystem::path(capture.metadata.images[i]).stem().string();
  }
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%03d_", index);
  return prefix + capture.metadata.patterns[i];
}

std::string percent(double fraction) {
  char text[16];
  std::snprintf(text, sizeof text, "%.0f%%", 100.0 * fraction);
  return text;
}

// The best explanation found so far for a disagreement.
// Phase steps are suspected first: a Gray bit must explain the images clearly better to replace
// them, by agreeing on more samples or by leaving clearly fewer jumps (depth edges jump under
// every reading). When the whole view lies within one stripe block of a coarse bit, undoing that
// bit and reversing the phase fit equally well; the message then names both.
constexpr double kTie = 0.02;         // agreement
constexpr double kFewerJumps = 0.75;  // jump share, relative

struct Suspect {
  Fit fit;
  std::string message;
  std::string alternative;  // an explanation that fits as well
  // Candidates that do not make the phase agree on most pixels explain nothing.
  void consider(const Fit& candidate, const std::string& explanation) {
    if (candidate.agreement < kExplained) return;
    const bool comparable = !message.empty() && candidate.agreement >= fit.agreement - kTie;
    if (message.empty() || candidate.agreement > fit.agreement + kTie ||
        (comparable && candidate.jumps < kFewerJumps * fit.jumps)) {
      fit = candidate;
      message = explanation;
      alternative.clear();
    } else if (comparable && candidate.jumps * kFewerJumps <= fit.jumps && alternative.empty()) {
      alternative = explanation;
    }
  }
};

void suspectGrayPairs(const io::Capture& capture, const AxisSamples& samples, const AxisLayout& axis, Suspect& best) {
  const std::vector<int> order = declaredOrder(samples.steps);
  for (int bit = 0; bit < axis.bits(); ++bit) {
    best.consider(fit(samples, axis, order, 1u << (axis.bits() - 1 - bit)),
                  "images " + imageLabel(capture, axis.bit_images[static_cast<std::size_t>(bit)]) + " and " +
                      imageLabel(capture, axis.inverse_images[static_cast<std::size_t>(bit)]) +
                      " are swapped (pattern and inverse)");
  }
}

void suspectPhaseSteps(const io::Capture& capture, const AxisSamples& samples, const AxisLayout& axis,
                       const std::string& axis_name, Suspect& best) {
  for (int a = 0; a < samples.steps; ++a) {
    for (int b = a + 1; b < samples.steps; ++b) {
      std::vector<int> order = declaredOrder(samples.steps);
      std::swap(order[static_cast<std::size_t>(a)], order[static_cast<std::size_t>(b)]);
      best.consider(fit(samples, axis, order, 0u),
                    axis_name + " phase steps out of order (step " + std::to_string(a) + " and step " +
                        std::to_string(b) + " swapped? images " +
                        imageLabel(capture, axis.phase_images[static_cast<std::size_t>(a)]) + " and " +
                        imageLabel(capture, axis.phase_images[static_cast<std::size_t>(b)]) + ")");
    }
  }
}

template <typename Pixel>
void checkAxis(const io::Capture& capture, const DecodePlan& plan, const AxisLayout& axis,
               const std::string& axis_name) {
  if (!axis.present || !axis.hasPhase()) return;
  const AxisSamples samples = sampleAxis<Pixel>(capture, plan, axis);
  if (samples.size() < kMinSamples) return;
  const double declared = fit(samples, axis, declaredOrder(samples.steps), 0u).agreement;
  if (declared >= kAgreeing) return;
  Suspect best;
  suspectPhaseSteps(capture, samples, axis, axis_name, best);
  suspectGrayPairs(capture, samples, axis, best);
  if (best.message.empty() || best.fit.agreement < declared + kGain) return;
  const std::string also = best.alternative.empty() ? "" : " (or " + best.alternative + ")";
  throw core::Error("capture: " + best.message + also + ": the phase agrees with the Gray code on " +
                    percent(declared) + " of the well-lit pixels as recorded, on " + percent(best.fit.agreement) +
                    " with them swapped back");
}

template <typename Pixel>
void checkAll(const io::Capture& capture, const DecodePlan& plan) {
  checkAxis<Pixel>(capture, plan, plan.layout.columns, "column");
  checkAxis<Pixel>(capture, plan, plan.layout.rows, "row");
}

}  // namespace

void checkCaptureOrder(const io::Capture& capture, const DecodePlan& plan) {
  if (plan.layout.bit_depth == 8) {
    checkAll<uint8_t>(capture, plan);
  } else {
    checkAll<uint16_t>(capture, plan);
  }
}

}  // namespace binpick::reconstruction::detail
