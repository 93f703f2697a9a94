#pragma once
// Edge pixels on the other side. A camera pixel gathers light over its area, widened by its lens's
// blur; beside a lit surface's edge, where that surface's projector shadow falls (or where nothing
// is seen), a pixel whose centre sees the dark side still takes in part of the lit edge, decodes
// the edge's light (the dark side adds none) and is triangulated on its own ray: its point lands
// beside the edge, on the extension of the lit surface, centimetres off the shadowed surface the
// pixel sees, and the surface looks a pixel or more wider on its shadow side. Its depth follows
// the surface, so the depth-step test of depth_edges.hpp keeps it. The same happens beside a
// dimmer lit surface at another depth (a bright part's rim over a darker floor): the brighter
// side's pattern wins the pixel's code. Which side a pixel's centre sees shows in its brightness:
// more than half of its own side's light above the other side's (the edge through its centre
// splits what it gathers in two).
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction::detail {

struct EdgeCoverageTest {
  int reach = 3;               // pixels behind a point searched for the other side
  float max_step = 8.0f;       // pixel footprints a pixel: a depth step up to this stays on a surface
  float min_contrast = 0.02f;  // white image, [0, 1]: sides less different in brightness are not judged
  float max_share = 0.5f;      // of its own side's light above the other side's: below it, removed
};

// One flag per point p: 1 where, along one of the 8 neighbour directions, the other side lies
// behind p within `reach` pixels (past points of p's own surface and pixels without a point): a
// pixel in projector shadow or seeing nothing (status Unlit), or a point off p's surface by more
// than a depth step of max_step footprints a pixel; the nearest point ahead of p within 2 pixels
// lies on p's surface and is at least min_contrast brighter (white image, cloud.intensities) than
// that other side; and p's brightness above the other side's is less than max_share of that
// neighbour's: p's centre sees the other side. The neighbour, not the surface's full brightness,
// is the reference: at a blurred edge the last pixel on the lit side gathers more than half of
// what its next one does, the first on the other side less (and a dimmer face beyond a crease of
// the lit surface is judged against itself, not the brighter face). A crease has no depth step,
// so its two faces are never each other's other side. No flags for a cloud without intensities.
// Rows in parallel on `threads` threads; the result does not depend on their number.
std::vector<uint8_t> findOtherSideEdgePixels(const io::PointCloud& cloud, const cv::Mat& status,
                                             const EdgeCoverageTest& test, int threads);

}  // namespace binpick::reconstruction::detail
