// estimateSensorNoise: a line through the residual variance of the Gray pairs against brightness.
#include "sensor_noise_estimate.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace binpick::reconstruction::detail {
namespace {

constexpr int kSampleStep = 6;       // every 6th pixel of every 6th row: tens of thousands of pixels
constexpr int kBins = 32;            // brightness bins the variance is averaged in
constexpr double kMinSamples = 200;  // fewer usable residuals: no estimate

struct Bins {
  std::array<double, kBins> signal{};  // sums of s, of r^2, and counts per bin
  std::array<double, kBins> squared{};
  std::array<double, kBins> count{};
};

template <typename Pixel>
Pixel valueAt(const io::Capture& capture, int image, int y, int x) {
  return capture.images[static_cast<std::size_t>(image)].at<Pixel>(y, x);
}

template <typename Pixel>
void addAxis(const io::Capture& capture, const AxisLayout& axis, int y, int x, float white, float black,
             float saturation, float top, Bins& bins) {
  if (!axis.present) return;
  for (int bit = 0; bit < axis.bits(); ++bit) {
    const float p = static_cast<float>(valueAt<Pixel>(capture, axis.bit_images[bit], y, x));
    const float q = static_cast<float>(valueAt<Pixel>(capture, axis.inverse_images[bit], y, x));
    if (p <= 0.0f || q <= 0.0f || p >= saturation || q >= saturation) continue;
    const float s = p + q + white + black;
    const float r = (p + q) - (white + black);
    const int bin = std::min(kBins - 1, static_cast<int>(s / top * kBins));
    bins.signal[bin] += s;
    bins.squared[bin] += static_cast<double>(r) * r;
    bins.count[bin] += 1.0;
  }
}

template <typename Pixel>
Bins collect(const io::Capture& capture, const CaptureLayout& layout, float saturation, float min_contrast) {
  Bins bins;
  const float top = 4.0f * saturation;  // the largest s of unclipped values
  for (int y = kSampleStep / 2; y < layout.height; y += kSampleStep) {
    for (int x = kSampleStep / 2; x < layout.width; x += kSampleStep) {
      const float white = static_cast<float>(valueAt<Pixel>(capture, layout.white, y, x));
      const float black = static_cast<float>(valueAt<Pixel>(capture, layout.black, y, x));
      if (white - black < min_contrast || white >= saturation || black <= 0.0f) continue;
      addAxis<Pixel>(capture, layout.columns, y, x, white, black, saturation, top, bins);
      addAxis<Pixel>(capture, layout.rows, y, x, white, black, saturation, top, bins);
    }
  }
  return bins;
}

// Weighted least squares of the bins' mean r^2 against their mean s: var(r) = 4 read + gain s
// (four images, each with read + gain * its signal; their signals add up to s).
SensorNoise fitLine(const Bins& bins) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int b = 0; b < kBins; ++b) {
    if (bins.count[b] < 1.0) continue;
    const double w = bins.count[b];
    const double x = bins.signal[b] / w, y = bins.squared[b] / w;
    n += w;
    sx += w * x;
    sy += w * y;
    sxx += w * x * x;
    sxy += w * x * y;
  }
  SensorNoise noise;
  if (n < kMinSamples) return noise;
  const double spread = n * sxx - sx * sx;
  double slope = spread > 1e-9 * n * sxx ? (n * sxy - sx * sy) / spread : 0.0;
  slope = std::max(0.0, slope);
  const double intercept = (sy - slope * sx) / n;
  // At least the rounding of one value (1/12 count^2), whatever the fit says.
  noise.read = static_cast<float>(std::max(1.0 / 12.0, intercept / 4.0));
  noise.gain = static_cast<float>(slope);
  noise.measured = true;
  return noise;
}

}  // namespace

SensorNoise estimateSensorNoise(const io::Capture& capture, const CaptureLayout& layout, float saturation,
                                float min_contrast) {
  const Bins bins = layout.bit_depth == 8 ? collect<uint8_t>(capture, layout, saturation, min_contrast)
                                          : collect<uint16_t>(capture, layout, saturation, min_contrast);
  return fitLine(bins);
}

}  // namespace binpick::reconstruction::detail
