#pragma once
// Depth-edge detection on an organized cloud: points that stand off the surface their neighbours
// describe, i.e. mixed pixels at depth edges (a camera pixel that sees part of a near and part of
// a far surface decodes to a position in between) and lone misdecoded points.
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction::detail {

// One flag per point: 1 where the point is finite, has at least `min_neighbours` finite
// 8-neighbours, its camera z differs from their median by more than max_jump * its z (the
// pixel's footprint grows with z, and so do the steps of a slanted surface between pixels), and
// fewer than `min_support` of them lie within that distance of it. The median of the neighbours
// of a point on any plane is the point's own z up to the perspective curvature, however steep the
// plane; at a depth edge it is one side's. The support keeps the last pixels of the near surface
// at an edge (their own surface continues beside them), which a mixed pixel, seeing neither
// surface, lacks. Rows in parallel on `threads` threads; the result does not depend on their
// number.
std::vector<uint8_t> findDepthEdgeOutliers(const io::PointCloud& cloud, float max_jump, int min_neighbours,
                                           int min_support, int threads);

}  // namespace binpick::reconstruction::detail
