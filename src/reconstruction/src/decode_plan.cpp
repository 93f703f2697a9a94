// The decoder's per-capture setup.
#include "decode_plan.hpp"

#include <cmath>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction::detail {
namespace {

DecodeThresholds thresholdsFor(const DecodeParams& params, int bit_depth) {
  const float counts = bit_depth == 16 ? 257.0f : 1.0f;
  DecodeThresholds t;
  t.min_contrast = static_cast<float>(params.min_contrast) * counts;
  t.min_direct = static_cast<float>(params.min_direct) * counts;
  t.black_level = static_cast<float>(params.projector_black_level);
  t.min_bit_difference = static_cast<float>(params.min_bit_difference) * counts;
  t.bit_margin = static_cast<float>(params.bit_margin);
  t.min_phase_amplitude = static_cast<float>(params.min_phase_amplitude) * counts;
  t.phase_tolerance = static_cast<float>(params.max_phase_gray_disagreement);
  // Half a count below the top: 16-bit images of 10-14 bit sensors top out below 65535.
  t.saturation = 254.5f * counts;
  t.full_scale = bit_depth == 16 ? 65535.0f : 255.0f;
  t.max_run_without_phase = params.max_code_run_without_phase;
  t.max_run_with_phase = params.max_code_run_with_phase;
  t.keep_column_without_row = params.keep_column_without_row;
  return t;
}

// The Gray pairs whose stripes are as wide as the settings ask, and at least the two finest: a
// pixel on the edge of one pair's stripe sees the other's lit or dark (with words of a whole
// period or half of one, AxisLayout::gray_unit, often one pair alone is in range).
void addSeparationImages(std::vector<int>& images, const AxisLayout& axis, const DecodeParams& params) {
  constexpr int kMinPairs = 2;
  const int first_image = static_cast<int>(images.size());
  for (int bit = axis.bits() - 1; bit >= 0; --bit) {
    const int stripe = axis.stripeWidth(bit);
    const bool in_range = stripe >= params.separation_min_stripe && stripe <= params.separation_max_stripe;
    const int pairs = (static_cast<int>(images.size()) - first_image) / 2;
    if (!in_range && !(pairs < kMinPairs && stripe > params.separation_max_stripe)) continue;
    images.push_back(axis.bit_images[bit]);
    images.push_back(axis.inverse_images[bit]);
  }
}

// The unwrapping window (the Gray-code run plus the tolerance on both sides) must be shorter
// than a period, or two period instances could fall inside it.
void checkUnwrappable(const AxisLayout& axis, const DecodeParams& params) {
  if (!axis.hasPhase()) return;
  const double window = params.max_code_run_with_phase + 2.0 * params.max_phase_gray_disagreement;
  if (window < axis.phase_period) return;
  throw core::Error("decode: phase period " + std::to_string(axis.phase_period) +
                    " px is too short to unwrap with max_code_run_with_phase " +
                    std::to_string(params.max_code_run_with_phase) + " and max_phase_gray_disagreement " +
                    std::to_string(params.max_phase_gray_disagreement));
}

PhaseWeights phaseWeights(const AxisLayout& axis, const io::PatternSetSpec& spec) {
  PhaseWeights weights;
  const int steps = static_cast<int>(axis.phase_images.size());
  for (int k = 0; k < steps; ++k) {
    const double shift = phaseShift(spec, k);
    weights.cosine.push_back(static_cast<float>(std::cos(shift)));
    weights.sine.push_back(static_cast<float>(std::sin(shift)));
  }
  return weights;
}

}  // namespace

DecodePlan makeDecodePlan(const CaptureLayout& layout, const DecodeParams& params) {
  checkUnwrappable(layout.columns, params);
  checkUnwrappable(layout.rows, params);
  DecodePlan plan;
  plan.layout = layout;
  plan.thresholds = thresholdsFor(params, layout.bit_depth);
  addSeparationImages(plan.separation_images, layout.columns, params);
  addSeparationImages(plan.separation_images, layout.rows, params);
  if (plan.separation_images.empty()) {
    // A projector too small for the requested stripes: its finest pair is the best estimate.
    const AxisLayout& columns = layout.columns;
    plan.separation_images = {columns.bit_images.back(), columns.inverse_images.back()};
  }
  // Both axes use the same number of steps (one PatternSetSpec).
  plan.phase = phaseWeights(layout.columns, layout.pattern_set);
  return plan;
}

}  // namespace binpick::reconstruction::detail
