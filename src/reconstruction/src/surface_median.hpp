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

// Per finite point with all 8 neighbours inside the image: the median camera z of the point and
// those neighbours within `reach` (metres) of its z (neighbours beyond it belong to another
// surface, across a depth edge, and take no part). If the median lies more than `max_pull`
// (metres) from the point's z, the point is flagged (returned 1) and left as it is; otherwise it is scaled along its ray onto the median. Border pixels are
// left as they are. Rows in parallel on `threads` threads; the result does not depend on their
// number.
// Points brighter than max_intensity (cloud.intensities, when it has them) are left as they are.
std::vector<uint8_t> smoothToSurfaceMedian(io::PointCloud& cloud, float reach, float max_pull, float max_intensity,
                                           int threads);

}  // namespace binpick::reconstruction::detail
