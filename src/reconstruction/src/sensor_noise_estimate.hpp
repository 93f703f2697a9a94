#pragma once
// The camera's noise, measured on the capture itself: a Gray pattern and its inverse add up to
// white + black wherever the projector reaches, so the residual (p + q) - (white + black) is pure
// sensor noise, whatever the scene. Its variance, over many pixels of many brightnesses, gives
// the sensor's read + shot model: var = read + gain * signal. Internal to the decoder.
#include "binpick/io/capture.hpp"
#include "capture_layout.hpp"

namespace binpick::reconstruction::detail {

struct SensorNoise {
  // Variance of one image's value at signal s (counts of the capture): read + gain * s.
  float read = 0.0f;      // counts^2, quantisation included
  float gain = 0.0f;      // counts
  bool measured = false;  // false: too few usable samples, the fields are 0
};

// Samples pixels on a sparse grid; skips the unlit and those where any of the four values is
// clipped at either end of the scale (their residual is not Gaussian). `saturation`: the
// capture's clip level; `min_contrast`: white - black below it is unlit (capture counts).
SensorNoise estimateSensorNoise(const io::Capture& capture, const CaptureLayout& layout, float saturation,
                                float min_contrast);

}  // namespace binpick::reconstruction::detail
