// Surface median: each point against the median of its 3x3 neighbourhood's surface.
#include "surface_median.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::reconstruction::detail {
namespace {

// The camera z of (x, y) and of its 8 neighbours within `reach` of it, into `depths`; returns
// their count (at least 1: the point itself).
int sameSurfaceDepths(const io::PointCloud& cloud, int x, int y, float z, float reach, float* depths) {
  int count = 0;
  for (int v = y - 1; v <= y + 1; ++v) {
    const Eigen::Vector3f* row = cloud.points.data() + static_cast<std::size_t>(v) * cloud.width;
    for (int u = x - 1; u <= x + 1; ++u) {
      const float q = row[u].z();
      if (std::fabs(q - z) <= reach) depths[count++] = q;  // NaN: never
    }
  }
  return count;
}

// Insertion sort: at most nine values, where it beats nth_element's set-up.
float medianOf(float* values, int count) {
  for (int i = 1; i < count; ++i) {
    const float value = values[i];
    int j = i;
    for (; j > 0 && values[j - 1] > value; --j) values[j] = values[j - 1];
    values[j] = value;
  }
  return values[count / 2];
}

}  // namespace

std::vector<uint8_t> smoothToSurfaceMedian(io::PointCloud& cloud, float reach, float max_pull, float max_intensity,
                                           int threads) {
  const bool gated = cloud.hasIntensities();
  const int width = cloud.width, height = cloud.height;
  std::vector<uint8_t> outlier(cloud.points.size(), 0);
  // Each point is decided on the depths as they came: the new ones wait here (0: unchanged).
  std::vector<float> scale(cloud.points.size(), 0.0f);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 1; y < height - 1; ++y) {
    float depths[9];
    for (int x = 1; x < width - 1; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      const float z = cloud.points[i].z();
      if (!std::isfinite(z) || (gated && !(cloud.intensities[i] <= max_intensity))) continue;
      const int count = sameSurfaceDepths(cloud, x, y, z, reach, depths);
      const float median = medianOf(depths, count);
      if (std::fabs(median - z) > max_pull) {
        outlier[i] = 1;
      } else {
        scale[i] = median / z;
      }
    }
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < static_cast<long>(scale.size()); ++i) {
    if (scale[i] != 0.0f) cloud.points[i] *= scale[i];
  }
  return outlier;
}

}  // namespace binpick::reconstruction::detail
