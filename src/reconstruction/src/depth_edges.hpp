#pragma once
// Depth-edge detection on an organized cloud: points that stand off the surface their neighbours
// describe, i.e. mixed pixels at depth edges (a camera pixel that sees part of a near and part of
// a far surface decodes to a position in between) and lone misdecoded points.
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "depth_step.hpp"

namespace binpick::reconstruction::detail {

// One flag per point: 1 where the point is finite, has at least `min_neighbours` finite
// 8-neighbours, and fewer than `min_support` of them lie within `max_jump` pixel footprints of its
// camera z (a footprint is z times the angle between adjacent rays, measured on the cloud: the
// steps of a slanted surface between pixels grow with it).
// A point of a surface has its surface around it: on a plane seen up to about 80 degrees from
// its normal, every neighbour but the diagonals across the slope lies within 8 footprints; the
// last pixels of a near surface at an edge keep those along the edge and inside. A mixed pixel,
// which sees neither surface, has at most the other mixed pixels along a 1-pixel veil; a lone
// misdecoded point has none. `coarse_step` (nullptr, or metres per point): a point whose decoding
// is coarser than that (DepthStep) has at least it as its reach. Rows in parallel on `threads`
// threads; the result does not depend on their number.
std::vector<uint8_t> findDepthEdgeOutliers(const io::PointCloud& cloud, float max_jump, int min_neighbours,
                                           int min_support, const float* coarse_step, int threads);

// The angle between the rays of horizontally adjacent pixels (1 / f for a pinhole), from the
// cloud itself: the median of |x/z - x'/z'| over adjacent points of every 8th row. 0 when the
// cloud has no adjacent points. A pixel's footprint at depth z is z times this.
float rayPitch(const io::PointCloud& cloud);

}  // namespace binpick::reconstruction::detail
