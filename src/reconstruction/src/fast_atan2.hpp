#pragma once
// An atan2 that the compiler vectorises (std::atan2 does not; needs -fno-trapping-math), accurate to about
// 1e-5 rad: a phase error of 1e-5 / (2 pi) of a period, far below the sensor noise.
#include <algorithm>
#include <cmath>

namespace binpick::reconstruction::detail {

inline float fastAtan2(float y, float x) {
  const float ax = std::fabs(x);
  const float ay = std::fabs(y);
  const float ratio = std::min(ax, ay) / (std::max(ax, ay) + 1e-30f);
  const float s = ratio * ratio;
  // Minimax polynomial of atan on [0, 1] (odd, degree 11).
  float angle = ((((((-0.0117212f * s + 0.05265332f) * s - 0.11643287f) * s + 0.19354346f) * s - 0.33262347f) * s +
                  0.99997726f)) *
                ratio;
  angle = ay > ax ? 1.57079637f - angle : angle;
  angle = x < 0.0f ? 3.14159274f - angle : angle;
  return y < 0.0f ? -angle : angle;
}

}  // namespace binpick::reconstruction::detail
