// The decoder's vectorised tile passes (tile_kernels.hpp). Equations cite Moreno & Taubin,
// "Simple, Accurate, and Robust Projector-Camera Calibration" (3DIMPVT 2012), section 3.
#include "tile_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "fast_atan2.hpp"
#include "simd_dispatch.hpp"

namespace binpick::reconstruction::detail {

template <typename Pixel>
BINPICK_SIMD_PASS void widenRange(const Pixel* __restrict values, float* __restrict high, float* __restrict low,
                                  int width) {
  for (int x = 0; x < width; ++x) {
    high[x] = std::max(high[x], static_cast<float>(values[x]));
    low[x] = std::min(low[x], static_cast<float>(values[x]));
  }
}

template <typename Pixel>
BINPICK_SIMD_PASS void separateLight(const Pixel* __restrict black, float b, float* __restrict high,
                                     float* __restrict low, int width) {
  const float direct_scale = 1.0f / (1.0f - b);
  const float global_scale = 2.0f / (1.0f - b * b);
  for (int x = 0; x < width; ++x) {
    const float k = static_cast<float>(black[x]);
    const float direct = (high[x] - low[x]) * direct_scale;
    low[x] = std::max(0.0f, ((low[x] - k) - b * (high[x] - k)) * global_scale);
    high[x] = direct;
  }
}

template <typename Pixel>
BINPICK_SIMD_PASS void flagPixels(const Pixel* __restrict white, const Pixel* __restrict black,
                                  const float* __restrict direct, const DecodeThresholds& t,
                                  float* __restrict intensity, uint8_t* __restrict lit,
                                  uint8_t* __restrict white_clipped, int width) {
  const float to_unit = 1.0f / t.full_scale;
  const float min_contrast = t.min_contrast;
  const float min_direct = t.min_direct;
  const float saturation = t.saturation;
  for (int x = 0; x < width; ++x) {
    const float k = static_cast<float>(black[x]);
    const float w = static_cast<float>(white[x]);
    intensity[x] = w * to_unit;
    lit[x] = static_cast<uint8_t>(static_cast<int>(w - k >= min_contrast) & static_cast<int>(direct[x] >= min_direct));
    white_clipped[x] = static_cast<uint8_t>(w >= saturation);
  }
}

template <typename Pixel, typename Work>
BINPICK_SIMD_PASS void addToBlack(const Pixel* __restrict black, const float* __restrict counts, Work* __restrict out,
                                  int width) {
  for (int x = 0; x < width; ++x) out[x] = level<Work>(static_cast<float>(black[x]) + counts[x]);
}

template <typename Pixel, typename Work>
BINPICK_SIMD_PASS void bitMargins(const float* __restrict direct, const Pixel* __restrict white,
                                  const Pixel* __restrict black, const DecodeThresholds& t, Work* __restrict out,
                                  int width) {
  const float least = t.min_bit_difference;
  const float ratio = t.bit_margin;
  const float floor = t.noise_floor;
  const float slope = t.noise_slope;
  for (int x = 0; x < width; ++x) {
    const float noise = std::sqrt(floor + slope * (static_cast<float>(white[x]) + static_cast<float>(black[x])));
    out[x] = ceilingLevel<Work>(std::max(least, std::min(ratio * direct[x], noise)));
  }
}

template <typename Work>
BINPICK_SIMD_PASS bool directLightOnly(const uint8_t* __restrict lit, const uint8_t* __restrict white_clipped,
                                       const Work* __restrict direct_level, const Work* __restrict global_level,
                                       int width) {
  int exceptions = 0;
  for (int x = 0; x < width; ++x) {
    exceptions += lit[x] & (white_clipped[x] | static_cast<uint8_t>(direct_level[x] <= global_level[x]));
  }
  return exceptions == 0;
}

template <typename Pixel, typename Work>
BINPICK_SIMD_PASS void classifyBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse,
                                   const Work* __restrict direct_level, const Work* __restrict global_level,
                                   const Work* __restrict margin, Work clip, uint16_t* __restrict code,
                                   uint16_t* __restrict uncertain, int width) {
  for (int x = 0; x < width; ++x) {
    const Work p = static_cast<Work>(pattern[x]);
    const Work q = static_cast<Work>(inverse[x]);
    const Work ld = direct_level[x];
    const Work lg = global_level[x];
    const Work difference = static_cast<Work>(p - q);
    const Work spread = difference < 0 ? static_cast<Work>(-difference) : difference;
    const uint16_t direct_dominates = ld > lg;
    const uint16_t brighter = p > q;
    const uint16_t on = static_cast<uint16_t>((p > lg) & (q < ld));
    const uint16_t off = static_cast<uint16_t>((p < ld) & (q > lg));
    const uint16_t value = static_cast<uint16_t>((direct_dominates & brighter) | ((1u - direct_dominates) & on));
    const uint16_t distinct = static_cast<uint16_t>((spread >= margin[x]) & ((p < clip) | (q < clip)));
    const uint16_t certain = static_cast<uint16_t>((direct_dominates | (on ^ off)) & distinct);
    code[x] = static_cast<uint16_t>((code[x] << 1) | value);
    uncertain[x] = static_cast<uint16_t>((uncertain[x] << 1) | (certain ^ 1u));
  }
}

template <typename Pixel, typename Work>
BINPICK_SIMD_PASS void classifyDirectBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse,
                                         const Work* __restrict margin, uint16_t* __restrict code,
                                         uint16_t* __restrict uncertain, int width) {
  for (int x = 0; x < width; ++x) {
    const Work difference = static_cast<Work>(static_cast<Work>(pattern[x]) - static_cast<Work>(inverse[x]));
    const Work spread = difference < 0 ? static_cast<Work>(-difference) : difference;
    code[x] = static_cast<uint16_t>((code[x] << 1) | static_cast<uint16_t>(difference > 0));
    uncertain[x] = static_cast<uint16_t>((uncertain[x] << 1) | static_cast<uint16_t>(spread < margin[x]));
  }
}

template <typename Pixel>
BINPICK_SIMD_PASS void accumulatePhase(const Pixel* __restrict values, float sine, float cosine,
                                       float* __restrict sine_sum, float* __restrict cosine_sum,
                                       float* __restrict brightest, int width) {
  for (int x = 0; x < width; ++x) {
    const float v = static_cast<float>(values[x]);
    sine_sum[x] += v * sine;
    cosine_sum[x] += v * cosine;
    brightest[x] = std::max(brightest[x], v);
  }
}

template <typename Pixel>
BINPICK_SIMD_PASS void phaseNoise(const Pixel* __restrict white, const Pixel* __restrict black,
                                  const float* __restrict amplitude, float read, float gain, float* __restrict noise,
                                  int width) {
  for (int x = 0; x < width; ++x) {
    const float signal = static_cast<float>(white[x]) + static_cast<float>(black[x]);
    noise[x] = std::sqrt(read + gain * signal) / amplitude[x];
  }
}

BINPICK_SIMD_PASS void phaseFromSums(const float* __restrict brightest, float clip, float to_amplitude, float to_pixels,
                                     float* __restrict sine_sum, float* __restrict cosine_sum,
                                     uint8_t* __restrict clipped, int width) {
  for (int x = 0; x < width; ++x) {
    const float sn = sine_sum[x];
    const float cs = cosine_sum[x];
    sine_sum[x] = fastAtan2(sn, cs) * to_pixels;
    cosine_sum[x] = to_amplitude * std::sqrt(sn * sn + cs * cs);
    clipped[x] = static_cast<uint8_t>(brightest[x] >= clip);
  }
}

template void widenRange<uint8_t>(const uint8_t*, float*, float*, int);
template void widenRange<uint16_t>(const uint16_t*, float*, float*, int);
template void separateLight<uint8_t>(const uint8_t*, float, float*, float*, int);
template void separateLight<uint16_t>(const uint16_t*, float, float*, float*, int);
template void addToBlack<uint8_t, int16_t>(const uint8_t*, const float*, int16_t*, int);
template void addToBlack<uint16_t, float>(const uint16_t*, const float*, float*, int);
template void bitMargins<uint8_t, int16_t>(const float*, const uint8_t*, const uint8_t*, const DecodeThresholds&,
                                           int16_t*, int);
template void bitMargins<uint16_t, float>(const float*, const uint16_t*, const uint16_t*, const DecodeThresholds&,
                                          float*, int);
template void flagPixels<uint8_t>(const uint8_t*, const uint8_t*, const float*, const DecodeThresholds&, float*,
                                  uint8_t*, uint8_t*, int);
template void flagPixels<uint16_t>(const uint16_t*, const uint16_t*, const float*, const DecodeThresholds&, float*,
                                   uint8_t*, uint8_t*, int);
template bool directLightOnly<int16_t>(const uint8_t*, const uint8_t*, const int16_t*, const int16_t*, int);
template bool directLightOnly<float>(const uint8_t*, const uint8_t*, const float*, const float*, int);
template void classifyBit<uint8_t, int16_t>(const uint8_t*, const uint8_t*, const int16_t*, const int16_t*,
                                            const int16_t*, int16_t, uint16_t*, uint16_t*, int);
template void classifyBit<uint16_t, float>(const uint16_t*, const uint16_t*, const float*, const float*, const float*,
                                           float, uint16_t*, uint16_t*, int);
template void classifyDirectBit<uint8_t, int16_t>(const uint8_t*, const uint8_t*, const int16_t*, uint16_t*, uint16_t*,
                                                  int);
template void classifyDirectBit<uint16_t, float>(const uint16_t*, const uint16_t*, const float*, uint16_t*, uint16_t*,
                                                 int);
template void phaseNoise<uint8_t>(const uint8_t*, const uint8_t*, const float*, float, float, float*, int);
template void phaseNoise<uint16_t>(const uint16_t*, const uint16_t*, const float*, float, float, float*, int);
template void accumulatePhase<uint8_t>(const uint8_t*, float, float, float*, float*, float*, int);
template void accumulatePhase<uint16_t>(const uint16_t*, float, float, float*, float*, float*, int);
}  // namespace binpick::reconstruction::detail
