// Depth-edge detection: each point against the depths of its 8-neighbourhood.
#include "depth_edges.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::reconstruction::detail {
namespace {

// The finite camera z of the 8-neighbours of (x, y), into `depths`; returns their count.
int neighbourDepths(const io::PointCloud& cloud, int x, int y, float* depths) {
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    const int v = y + dy;
    if (v < 0 || v >= cloud.height) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = x + dx;
      if ((dx == 0 && dy == 0) || u < 0 || u >= cloud.width) continue;
      const float z = cloud.points[static_cast<std::size_t>(v) * cloud.width + u].z();
      if (std::isfinite(z)) depths[count++] = z;
    }
  }
  return count;
}

// How many of `count` depths lie within `reach` of z.
int support(const float* depths, int count, float z, float reach) {
  int near = 0;
  for (int k = 0; k < count; ++k) near += std::fabs(depths[k] - z) <= reach ? 1 : 0;
  return near;
}

}  // namespace

float rayPitch(const io::PointCloud& cloud) {
  std::vector<float> pitches;
  for (int y = 0; y < cloud.height; y += 8) {
    for (int x = 0; x + 1 < cloud.width; ++x) {
      const Eigen::Vector3f& p = cloud.points[static_cast<std::size_t>(y) * cloud.width + x];
      const Eigen::Vector3f& q = cloud.points[static_cast<std::size_t>(y) * cloud.width + x + 1];
      if (p.allFinite() && q.allFinite()) pitches.push_back(std::fabs(q.x() / q.z() - p.x() / p.z()));
    }
  }
  if (pitches.empty()) return 0.0f;
  std::nth_element(pitches.begin(), pitches.begin() + static_cast<long>(pitches.size() / 2), pitches.end());
  return pitches[pitches.size() / 2];
}

std::vector<uint8_t> findDepthEdgeOutliers(const io::PointCloud& cloud, float max_jump, int min_neighbours,
                                           int min_support, const float* coarse_step, int threads) {
  const DepthStep step{0.0f, coarse_step};
  std::vector<uint8_t> outlier(cloud.points.size(), 0);
  const float reach_per_metre = max_jump * rayPitch(cloud);  // footprints -> a share of z
  if (!(reach_per_metre > 0.0f)) return outlier;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 0; y < cloud.height; ++y) {
    float depths[8];
    for (int x = 0; x < cloud.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * cloud.width + x;
      const float z = cloud.points[i].z();
      if (!std::isfinite(z)) continue;
      const int count = neighbourDepths(cloud, x, y, depths);
      if (count < min_neighbours) continue;
      outlier[i] = support(depths, count, z, step.at(i, reach_per_metre * z)) < min_support ? 1 : 0;
    }
  }
  return outlier;
}

}  // namespace binpick::reconstruction::detail
