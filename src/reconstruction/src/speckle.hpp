#pragma once
// Speckle detection on an organized cloud: connected patches of the pixel grid, grown between
// 4-neighbours whose camera z differs by at most a step (depth_step.hpp).
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "depth_step.hpp"

namespace binpick::reconstruction::detail {

// One flag per point: 1 where the point is finite and its patch has fewer than `min_pixels`
// points. O(N): horizontal runs, then union-find over the runs (no recursion, no per-pixel
// queue), in bands of rows on `threads` threads; the result does not depend on their number.
std::vector<uint8_t> findSpeckles(const io::PointCloud& cloud, const DepthStep& step, int min_pixels, int threads);

}  // namespace binpick::reconstruction::detail
