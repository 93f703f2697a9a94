#include "sensor_noise.hpp"

#include <cmath>
#include <limits>

#include "random.hpp"

namespace binpick::simulation::detail {
namespace {

void applyToPoint(Eigen::Vector3f& point, double sigma, double dropout, SplitMix64& rng) {
  if (dropout > 0.0 && uniform01(rng) < dropout) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    point = Eigen::Vector3f(nan, nan, nan);
    return;
  }
  if (sigma > 0.0) {
    // The camera is at the origin, so the ray through the point is the point's own direction.
    const Eigen::Vector3d p = point.cast<double>();
    point = (p * (1.0 + sigma * standardNormal(rng) / p.norm())).cast<float>();
  }
}

}  // namespace

void applySensorNoise(io::PointCloud& cloud, double sigma, double dropout, uint64_t seed, uint32_t stream) {
  if (sigma <= 0.0 && dropout <= 0.0) return;
  const KeyedStreams streams(seed, stream);
  // Keyed by point index, so the loop could be split among threads without changing the result.
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    Eigen::Vector3f& point = cloud.points[i];
    if (!point.allFinite()) continue;
    SplitMix64 rng = streams.forItem(i);
    applyToPoint(point, sigma, dropout, rng);
  }
}

}  // namespace binpick::simulation::detail
