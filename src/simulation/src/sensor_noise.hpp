#pragma once
// What the depth sensor adds to a perfect render: range noise and lost pixels.
// Internal to binpick::simulation. Pure: thread-safe.
#include <cstdint>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation::detail {

// For each valid point: with probability `dropout` it becomes NaN, otherwise it moves along its
// viewing ray by a Gaussian distance of standard deviation `sigma` (metres). The random numbers
// of point i come from KeyedStreams(seed, stream).forItem(i), so the result is fixed by the seed
// however the points are shared among threads.
void applySensorNoise(io::PointCloud& cloud, double sigma, double dropout, uint64_t seed, uint32_t stream);

}  // namespace binpick::simulation::detail
