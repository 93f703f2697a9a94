// The vectorised part of resolveAxis (axis_resolution.hpp).
#include "axis_resolution.hpp"

#include "simd_dispatch.hpp"

namespace binpick::reconstruction::detail {

BINPICK_SIMD_PASS void resolveSimpleRuns(const uint16_t* __restrict code, const uint16_t* __restrict uncertain,
                                         const AxisLayout& axis, const DecodeThresholds& t, float* __restrict centre,
                                         uint8_t* __restrict verdict, int width) {
  const int longest = longestRun(axis, t);
  const int last_index = axis.size - 1;
  const int unit = axis.gray_unit;
  for (int x = 0; x < width; ++x) {
    const uint32_t u = uncertain[x];
    const uint32_t low = grayDecode16(code[x] & ~u);
    const uint32_t high = grayDecode16(code[x] | u);
    const int first = static_cast<int>(std::min(low, high)) * unit;
    const int last = static_cast<int>(std::max(low, high)) * unit + unit - 1;
    const bool simple = ((u & (u - 1)) == 0) & (last - first < longest) & (first <= last_index);
    centre[x] = 0.5f * static_cast<float>(first + std::min(last, last_index));
    verdict[x] = simple ? static_cast<uint8_t>(PixelStatus::Valid) : kNeedsFullResolution;
  }
}

BINPICK_SIMD_PASS void unwrapSimpleRuns(const uint16_t* __restrict code, const uint16_t* __restrict uncertain,
                                        const float* __restrict phase_offset, const float* __restrict phase_amplitude,
                                        const uint8_t* __restrict phase_clipped, const AxisLayout& axis,
                                        const DecodeThresholds& t, float* __restrict position,
                                        uint8_t* __restrict verdict, int width) {
  const float period = static_cast<float>(axis.phase_period);
  const float inverse_period = 1.0f / period;
  const float reach = 0.5f + t.phase_tolerance;
  const float min_amplitude = t.min_phase_amplitude;
  const int last_index = axis.size - 1;
  const int unit = axis.gray_unit;
  for (int x = 0; x < width; ++x) {
    const uint32_t u = uncertain[x];
    const uint32_t low = grayDecode16(code[x] & ~u);
    const uint32_t high = grayDecode16(code[x] | u);
    const float first = static_cast<float>(static_cast<int>(std::min(low, high)) * unit);
    const float last =
        static_cast<float>(std::min(static_cast<int>(std::max(low, high)) * unit + unit - 1, last_index));
    const float centre = position[x];
    const float offset = phase_offset[x];
    const float unwrapped = offset + period * nearestWhole((centre - offset) * inverse_period);
    const bool inside =
        (unwrapped >= first - reach) & (unwrapped <= last + reach) & (phase_amplitude[x] >= min_amplitude);
    const uint8_t status = phase_clipped[x]
                               ? static_cast<uint8_t>(PixelStatus::Saturated)
                               : static_cast<uint8_t>(inside ? PixelStatus::Valid : PixelStatus::PhaseMismatch);
    position[x] = unwrapped;
    verdict[x] = verdict[x] == kNeedsFullResolution ? kNeedsFullResolution : status;
  }
}

}  // namespace binpick::reconstruction::detail
