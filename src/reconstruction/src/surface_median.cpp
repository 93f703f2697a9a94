// Surface median: each point against the median of its 3x3 neighbourhood's surface.
#include "surface_median.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace binpick::reconstruction::detail {
namespace {

// The camera z of (x, y), and for each of the four lines of its 3x3 neighbourhood through it
// (the row, the column, the diagonals) whose two ends both lie within `reach` of it, the mean of
// the two ends, into `depths`; returns their count (at least 1: the point itself). The mean of
// opposite neighbours is the surface's depth at the point wherever the surface is locally a plane,
// however steep: a point on the slope of a part's side is not pulled up or down the slope (a
// median of the neighbours themselves is, towards the side with more of them within reach: the
// floor beside the foot of the slope). A line with one end across a depth edge (beyond `reach`,
// or missing) takes no part: a point beside an edge is never drawn towards the other surface.
int surfaceDepths(const io::PointCloud& cloud, int x, int y, float z, float reach, float* depths) {
  const auto row = static_cast<std::ptrdiff_t>(cloud.width);
  const Eigen::Vector3f* centre = cloud.points.data() + y * row + x;
  const std::ptrdiff_t lines[4] = {1, row, row + 1, row - 1};
  int count = 0;
  depths[count++] = z;
  for (const std::ptrdiff_t step : lines) {
    const float a = centre[step].z(), b = centre[-step].z();
    if (std::fabs(a - z) <= reach && std::fabs(b - z) <= reach) depths[count++] = 0.5f * (a + b);  // NaN: never
  }
  return count;
}

// Insertion sort: at most five values, where it beats nth_element's set-up.
float medianOf(float* values, int count) {
  for (int i = 1; i < count; ++i) {
    const float value = values[i];
    int j = i;
    for (; j > 0 && values[j - 1] > value; --j) values[j] = values[j - 1];
    values[j] = value;
  }
  const int half = count / 2;
  return count % 2 == 1 ? values[half] : 0.5f * (values[half - 1] + values[half]);
}

}  // namespace

std::vector<uint8_t> smoothToSurfaceMedian(io::PointCloud& cloud, float reach, float max_pull, const MedianGate& gate,
                                           int threads) {
  const bool gated = cloud.hasIntensities();
  const int width = cloud.width, height = cloud.height;
  std::vector<uint8_t> outlier(cloud.points.size(), 0);
  // Each point is decided on the depths as they came: the moves wait here, per band of rows.
  std::vector<std::vector<std::pair<std::size_t, float>>> moves(static_cast<std::size_t>(height));
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 1; y < height - 1; ++y) {
    float depths[5];
    for (int x = 1; x < width - 1; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      // The noise first: it is NaN wherever there is no point, and most points are quiet.
      if (gate.noise != nullptr && !(gate.noise[i] >= gate.min_noise)) continue;
      if (gated && !(cloud.intensities[i] <= gate.max_intensity)) continue;
      const float z = cloud.points[i].z();
      if (!std::isfinite(z)) continue;
      const int count = surfaceDepths(cloud, x, y, z, reach, depths);
      const float median = medianOf(depths, count);
      // A noisy point on no line of its neighbourhood's surface has nothing to be smoothed or
      // checked with: beyond gate.lone_max_noise its noise alone may carry it millimetres off.
      const bool lone = count == 1 && gate.noise != nullptr && gate.noise[i] > gate.lone_max_noise;
      if (lone || std::fabs(median - z) > max_pull) {
        outlier[i] = 1;
      } else if (median != z) {
        moves[static_cast<std::size_t>(y)].emplace_back(i, median / z);
      }
    }
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 1; y < height - 1; ++y) {
    for (const auto& [i, scale] : moves[static_cast<std::size_t>(y)]) cloud.points[i] *= scale;
  }
  return outlier;
}

}  // namespace binpick::reconstruction::detail
