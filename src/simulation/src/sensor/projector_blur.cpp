#include "projector_blur.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::simulation::detail {
namespace {

constexpr float kSigmaFloor = 1e-3f;  // below this the blur is a box: one pixel's light
constexpr float kSpan = 3.0f;         // taps cover +-3 sigma: 99.7% of the Gaussian

float gaussianCdf(float t) { return 0.5f * (1.0f + std::erf(t * 0.70710678f)); }

}  // namespace

BlurTaps blurTaps(float x, float sigma, int size) {
  BlurTaps taps;
  if (!std::isfinite(x) || !std::isfinite(sigma)) return taps;
  sigma = std::clamp(sigma, kSigmaFloor, kMaxBlurSigma);
  // Far outside the projector image nothing arrives; returning here also keeps the float -> int
  // conversions below in range for huge coordinates (a grazing or distant surface point).
  const float reach = kSpan * sigma + 1.0f;
  if (x < -reach || x > static_cast<float>(size) + reach) return taps;
  const int lo = std::max(0, static_cast<int>(std::floor(x - kSpan * sigma + 0.5f)));
  const int hi = std::min(size - 1, static_cast<int>(std::floor(x + kSpan * sigma + 0.5f)));
  if (hi < lo) return taps;
  taps.first = lo;
  taps.count = std::min(hi - lo + 1, kMaxBlurTaps);
  const float inverse = 1.0f / sigma;
  float lower = gaussianCdf((static_cast<float>(lo) - 0.5f - x) * inverse);
  for (int k = 0; k < taps.count; ++k) {
    const float upper = gaussianCdf((static_cast<float>(lo + k) + 0.5f - x) * inverse);
    taps.weight[k] = upper - lower;
    lower = upper;
  }
  return taps;
}

}  // namespace binpick::simulation::detail
