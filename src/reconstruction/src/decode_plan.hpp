#pragma once
// Everything the tile decoder needs that depends only on the capture's layout and the params:
// image indices per role, thresholds in the images' own counts, phase weights. Internal.
#include <cstdint>
#include <limits>
#include <vector>

#include "binpick/reconstruction/decoder.hpp"
#include "capture_layout.hpp"

namespace binpick::reconstruction::detail {

// DecodeParams in the capture's counts (16-bit images: 257 per 8-bit count).
struct DecodeThresholds {
  float min_contrast = 0.0f;
  float min_direct = 0.0f;
  float black_level = 0.0f;  // Moreno & Taubin's b (a ratio, not counts)
  float min_bit_difference = 0.0f;
  float bit_margin = 0.0f;  // a ratio of L_d
  // The noise cap of the margin, squared, at a pixel: noise_floor + noise_slope * (white + black),
  // that is bit_noise_sigmas^2 * var(pattern - inverse). Infinite (no cap) unless the capture's
  // noise was measured.
  float noise_floor = std::numeric_limits<float>::infinity();
  float noise_slope = 0.0f;
  // The column's noise: sqrt(column_noise_read + column_noise_gain * (white + black)) over the
  // phase amplitude, in projector pixels (DecodedCapture::column_noise). NaN: not estimated.
  float column_noise_read = std::numeric_limits<float>::quiet_NaN();
  float column_noise_gain = 0.0f;
  float min_phase_amplitude = 0.0f;
  float phase_tolerance = 0.0f;  // projector pixels
  float saturation = 0.0f;       // a value at or above it was clipped by the sensor
  float full_scale = 255.0f;
  int max_run_without_phase = 2;
  int max_run_with_phase = 4;
  bool keep_column_without_row = true;
};

struct PhaseWeights {
  std::vector<float> cosine;  // cos(theta_k) per step (phaseShift, pattern_set.hpp)
  std::vector<float> sine;
};

struct DecodePlan {
  CaptureLayout layout;
  DecodeThresholds thresholds;
  // Images whose per-pixel max and min give L_max and L_min (Moreno & Taubin).
  std::vector<int> separation_images;
  PhaseWeights phase;
};

// Throws core::Error when a phase period is too short to be unwrapped by the Gray-code run
// the params allow.
DecodePlan makeDecodePlan(const CaptureLayout& layout, const DecodeParams& params);

}  // namespace binpick::reconstruction::detail
