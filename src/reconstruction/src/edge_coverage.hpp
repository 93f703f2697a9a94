#pragma once
// Edge pixels on the dark side. A camera pixel gathers light over its area, widened by its lens's
// blur; beside a lit surface's edge, where that surface's projector shadow falls (or where nothing
// is seen), a pixel whose centre sees the dark side still takes in part of the lit edge, decodes
// the edge's light (the dark side adds none) and is triangulated on its own ray: its point lands
// beside the edge, on the extension of the lit surface, centimetres off the shadowed surface the
// pixel sees, and the surface looks a pixel or more wider on its shadow side. Its depth follows
// the surface, so the depth-step test of depth_edges.hpp keeps it. Which side a pixel's centre
// sees shows in its brightness: more than half of the lit side's light above the dark side's
// (the edge through its centre splits what it gathers in two).
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction::detail {

struct EdgeCoverageTest {
  int reach = 3;               // pixels behind a point searched for the dark side
  float max_step = 8.0f;       // pixel footprints a pixel: a depth step up to this stays on a surface
  float min_contrast = 0.02f;  // white image, [0, 1]: sides less different in brightness are not judged
  float max_share = 0.5f;      // of the lit neighbour's light above the dark side's: below it, removed
};

// One flag per point p: 1 where, along one of the 8 neighbour directions, a pixel in projector
// shadow or seeing nothing (status Unlit) lies behind p within `reach` pixels (past points of p's
// own surface and pixels without a point), the nearest point ahead of p within 2 pixels lies on
// p's surface and is at least min_contrast brighter (white image, cloud.intensities) than that
// dark pixel, and p's brightness above the dark pixel's is less than max_share of that
// neighbour's: p's centre sees the dark side. The neighbour, not the surface's full brightness,
// is the reference: at a blurred edge the last pixel on the lit side gathers more than half of
// what its next one does, the first on the dark side less (and a dimmer face beyond a crease of
// the lit surface is judged against itself, not the brighter face). No flags for a cloud without
// intensities. Rows in parallel on `threads` threads; the result does not depend on their number.
std::vector<uint8_t> findDarkSideEdgePixels(const io::PointCloud& cloud, const cv::Mat& status,
                                            const EdgeCoverageTest& test, int threads);

}  // namespace binpick::reconstruction::detail
