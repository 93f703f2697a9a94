#pragma once
// The decoder's vectorised tile passes: small functions with restrict arguments over a tile's
// pixels, written without branches (0/1 integers, selects). GCC vectorises these (and not one
// loop doing it all, nor loops through local restrict pointers), and BINPICK_SIMD_PASS compiles
// them for AVX2 too. Pixel/Work pairs: (uint8_t, int16_t) and (uint16_t, float). Equations cite
// Moreno & Taubin, "Simple, Accurate, and Robust Projector-Camera Calibration" (3DIMPVT 2012),
// section 3. Internal.
#include <cstdint>
#include <type_traits>

#include "decode_plan.hpp"

namespace binpick::reconstruction::detail {

// Counts (>= 0) in the classification's arithmetic: rounded for integers.
template <typename Work>
inline Work level(float counts) {
  if constexpr (std::is_integral_v<Work>) {
    return static_cast<Work>(static_cast<int>(counts + 0.5f));
  } else {
    return counts;
  }
}

// A margin (>= 0) in the classification's arithmetic: rounded up for integers, so that
// |p - q| >= margin means the same as in real numbers.
template <typename Work>
inline Work ceilingLevel(float counts) {
  if constexpr (std::is_integral_v<Work>) {
    const int whole = static_cast<int>(counts);
    return static_cast<Work>(whole + static_cast<int>(static_cast<float>(whole) < counts));
  } else {
    return counts;
  }
}

// Light. `high`/`low` collect L_max/L_min over the high-frequency images; separateLight turns
// them into L_d = (L_max - L_min) / (1 - b) and L_g = 2 (L_min - b L_max) / (1 - b^2) above black.
template <typename Pixel>
void widenRange(const Pixel* __restrict values, float* __restrict high, float* __restrict low, int width);
template <typename Pixel>
void separateLight(const Pixel* __restrict black, float b, float* __restrict high, float* __restrict low, int width);
// out = black + counts, as a level.
template <typename Pixel, typename Work>
void addToBlack(const Pixel* __restrict black, const float* __restrict counts, Work* __restrict out, int width);
// The smallest |p - q| that classifies a bit: max(least, ratio * L_d, sqrt(noise_floor +
// noise_slope * (white + black))), the last a multiple of the noise of p - q.
template <typename Pixel, typename Work>
void bitMargins(const float* __restrict direct, const Pixel* __restrict white, const Pixel* __restrict black,
                const DecodeThresholds& t, Work* __restrict out, int width);
// Intensity, whether the pixel has projector light at all, and whether the sensor clipped it.
template <typename Pixel>
void flagPixels(const Pixel* __restrict white, const Pixel* __restrict black, const float* __restrict direct,
                const DecodeThresholds& t, float* __restrict intensity, uint8_t* __restrict lit,
                uint8_t* __restrict white_clipped, int width);
// Whether every lit pixel is unclipped and lit more directly than globally, so that
// classifyDirectBit classifies its bits exactly as classifyBit would.
template <typename Work>
bool directLightOnly(const uint8_t* __restrict lit, const uint8_t* __restrict white_clipped,
                     const Work* __restrict direct_level, const Work* __restrict global_level, int width);

// Bits. One Gray bit against its inverse (raw p, q) after Xu & Aliaga as used by Moreno & Taubin:
// where direct light dominates (L_d > L_g) the brighter one wins; where global light dominates,
// only p < L_d with q > L_g (off) or p > L_g with q < L_d (on) is trusted. Near-ties and pairs the
// sensor clipped are uncertain. The levels include black, so raw values compare directly. Shifts
// the bit into `code` and its doubt into `uncertain`.
template <typename Pixel, typename Work>
void classifyBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse, const Work* __restrict direct_level,
                 const Work* __restrict global_level, const Work* __restrict margin, Work clip,
                 uint16_t* __restrict code, uint16_t* __restrict uncertain, int width);
// The same for tiles where directLightOnly holds (most tiles of a bin): the brighter of pattern
// and inverse wins, near-ties are uncertain. A third of the work.
template <typename Pixel, typename Work>
void classifyDirectBit(const Pixel* __restrict pattern, const Pixel* __restrict inverse, const Work* __restrict margin,
                       uint16_t* __restrict code, uint16_t* __restrict uncertain, int width);

// Phase. Adds one step I_k to the sums of I_k sin(2 pi k/N) and I_k cos(2 pi k/N) and tracks the
// brightest step; phaseFromSums turns the sums, in place, into the phase offset (projector pixels
// within a period, phi = atan2(S, C)) and the amplitude B = 2/N |(S, C)|.
template <typename Pixel>
void accumulatePhase(const Pixel* __restrict values, float sine, float cosine, float* __restrict sine_sum,
                     float* __restrict cosine_sum, float* __restrict brightest, int width);
// The standard deviation of the phase's position (projector pixels): sqrt(read + gain * (white +
// black)) / amplitude, the two constants folding in the steps and the period.
template <typename Pixel>
void phaseNoise(const Pixel* __restrict white, const Pixel* __restrict black, const float* __restrict amplitude,
                float read, float gain, float* __restrict noise, int width);
void phaseFromSums(const float* __restrict brightest, float clip, float to_amplitude, float to_pixels,
                   float* __restrict sine_sum, float* __restrict cosine_sum, uint8_t* __restrict clipped, int width);

}  // namespace binpick::reconstruction::detail
