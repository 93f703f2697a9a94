// Edge pixels on the other side: brightness against the other side behind and the surface ahead.
#include "edge_coverage.hpp"

#include <array>
#include <cmath>

#include "binpick/reconstruction/pixel_status.hpp"
#include "depth_edges.hpp"

namespace binpick::reconstruction::detail {
namespace {

struct Step {
  int dx = 0;
  int dy = 0;
};

constexpr std::array<Step, 8> kSteps = {{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

// How far ahead a point's own surface is looked for: its next pixel may have lost its point.
constexpr int kSurfaceReach = 2;

struct Neighbourhood {
  const io::PointCloud& cloud;
  const cv::Mat& status;
  float step_per_metre;  // max_step footprints as a share of depth

  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < cloud.width && y < cloud.height; }
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * cloud.width + x; }
};

// The brightness of the other side behind (x, y) against `step`, or NaN: the first pixel within
// `reach` in projector shadow or seeing nothing (status Unlit), or the first point off the
// surface at depth z (another lit surface, nearer or further), past other points of that surface
// (edge pixels that gather its light too; a depth step up to max_step footprints a pixel) and
// pixels without a point (see edge_coverage.hpp).
float otherSideBehind(const Neighbourhood& n, int x, int y, float z, float brightness, Step step, int reach,
                      float min_contrast) {
  float last = z;  // the depth of the surface's last point met, and how many pixels back it was
  int gap = 0;
  for (int k = 1; k <= reach; ++k) {
    const int u = x - k * step.dx, v = y - k * step.dy;
    if (!n.inside(u, v)) break;
    ++gap;
    const std::size_t j = n.at(u, v);
    if (n.status.at<uint8_t>(v, u) == static_cast<uint8_t>(PixelStatus::Unlit)) return n.cloud.intensities[j];
    const float other = n.cloud.points[j].z();
    if (!std::isfinite(other)) continue;
    if (std::fabs(other - last) > n.step_per_metre * last * static_cast<float>(gap)) return n.cloud.intensities[j];
    // Across a blurred edge the light falls towards the dark side; a point behind as bright as
    // this one is more of its surface (a dim face beyond a crease), not a blurred edge.
    if (n.cloud.intensities[j] > brightness - min_contrast) break;
    last = other;
    gap = 0;
  }
  return std::nanf("");
}

// The brightness of the nearest point ahead of (x, y) along `step` if it lies on the surface at
// depth z, else NaN.
float surfaceAhead(const Neighbourhood& n, int x, int y, float z, Step step) {
  for (int k = 1; k <= kSurfaceReach; ++k) {
    const int u = x + k * step.dx, v = y + k * step.dy;
    if (!n.inside(u, v)) break;
    const std::size_t j = n.at(u, v);
    const float other = n.cloud.points[j].z();
    if (!std::isfinite(other)) continue;
    return std::fabs(other - z) <= n.step_per_metre * z * static_cast<float>(k) ? n.cloud.intensities[j]
                                                                                : std::nanf("");
  }
  return std::nanf("");
}

bool seesTheOtherSide(const Neighbourhood& n, int x, int y, const EdgeCoverageTest& test) {
  const std::size_t i = n.at(x, y);
  const float z = n.cloud.points[i].z(), here = n.cloud.intensities[i];
  for (const Step step : kSteps) {
    // here = w * own + (1 - w) * other, w the share of the pixel's light from its own surface
    // (which its point is on): judged only where its own surface is the brighter.
    const float other = otherSideBehind(n, x, y, z, here, step, test.reach, test.min_contrast);
    if (std::isnan(other)) continue;
    const float own = surfaceAhead(n, x, y, z, step);
    if (!(own - other >= test.min_contrast)) continue;
    if (here - other < test.max_share * (own - other)) return true;
  }
  return false;
}

}  // namespace

std::vector<uint8_t> findOtherSideEdgePixels(const io::PointCloud& cloud, const cv::Mat& status,
                                             const EdgeCoverageTest& test, int threads) {
  std::vector<uint8_t> flagged(cloud.points.size(), 0);
  const Neighbourhood n{cloud, status, test.max_step * rayPitch(cloud)};
  if (!cloud.hasIntensities() || test.reach < 1 || !(n.step_per_metre > 0.0f)) return flagged;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (int y = 0; y < cloud.height; ++y) {
    for (int x = 0; x < cloud.width; ++x) {
      if (cloud.points[n.at(x, y)].allFinite()) flagged[n.at(x, y)] = seesTheOtherSide(n, x, y, test) ? 1 : 0;
    }
  }
  return flagged;
}

}  // namespace binpick::reconstruction::detail
