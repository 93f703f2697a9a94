#pragma once
// Noise removal on an organized cloud: each point is moved along its camera ray to the median
// depth of its 3x3 neighbourhood's surface, and a point that stands too far from that median is
// flagged. On a dark or glossy part the depth noise breaks the surface into small patches (the
// speckle filter then takes them) and its tail reaches several millimetres; the median of nine
// samples has about half the spread and no such tail.
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction::detail {

// Per finite point with all 8 neighbours inside the image: the median of the point's camera z and,
// for each line of its 3x3 neighbourhood through it (row, column, diagonals) whose two ends lie
// within `reach` (metres) of its z, the mean of the two ends: the surface's depth at the point
// where it is locally a plane, however steep. Ends beyond `reach` belong to another surface,
// across a depth edge, and their line takes no part. If the median lies more than `max_pull`
// (metres) from the point's z, or the point is on no such line and its gate.noise exceeds
// gate.lone_max_noise, the point is flagged (returned 1) and left as it is; otherwise it is scaled
// along its ray onto the median. Border pixels are left as they are. Rows in parallel on
// `threads` threads; the result does not depend on their number.
// Points brighter than gate.max_intensity (cloud.intensities, when it has them), and points whose
// gate.noise is below gate.min_noise (NaN: not smoothed), are left as they are.
struct MedianGate {
  float max_intensity = 0.0f;    // cloud.intensities, when it has them
  const float* noise = nullptr;  // per pixel (row-major), or null: no noise gate
  float min_noise = 0.0f;
  float lone_max_noise = 0.0f;  // with noise: a point on no line beyond this is flagged
};
std::vector<uint8_t> smoothToSurfaceMedian(io::PointCloud& cloud, float reach, float max_pull, const MedianGate& gate,
                                           int threads);

}  // namespace binpick::reconstruction::detail
