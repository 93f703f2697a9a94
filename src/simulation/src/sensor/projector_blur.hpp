#pragma once
// Internal: how a defocused projector spreads its pixels over a surface point. Pure: thread-safe.
#include <array>

namespace binpick::simulation::detail {

// Sigmas are capped here; wider blur would wash out every Gray-code bit anyway.
constexpr float kMaxBlurSigma = 2.5f;
constexpr int kMaxBlurTaps = 18;

// Weights of the projector pixels [first, first + count) at continuous coordinate x: the share of
// a Gaussian (sigma, projector pixels) centred at x that falls on each pixel [j - 0.5, j + 0.5].
// Pixels outside [0, size) emit nothing and are left out (the weights then sum to less than 1).
struct BlurTaps {
  int first = 0;
  int count = 0;
  std::array<float, kMaxBlurTaps> weight{};
};

BlurTaps blurTaps(float x, float sigma, int size);

}  // namespace binpick::simulation::detail
