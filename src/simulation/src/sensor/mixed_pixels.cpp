// computeMixedPixels: edge pixels of the one-ray view, traced again over their area.
#include "mixed_pixels.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace binpick::simulation::detail {
namespace {

// A depth step this many pixel footprints (z / f) high between neighbouring pixels is an edge.
// A plane seen up to 83 degrees from its normal steps less (tan 83 < 8): the bin's walls, seen at
// 75 to 80 degrees, are not traced again for nothing.
constexpr float kEdgeStepFootprints = 8.0f;
constexpr double kInverseSqrtTwoPi = 0.39894228040143267794;

bool differ(const SensorGeometry& g, std::size_t a, std::size_t b, float step_per_metre) {
  if (g.object_index[a] != g.object_index[b]) return true;  // another object, or nothing and something
  if (g.object_index[a] < 0) return false;                  // nothing on either side
  return std::fabs(g.depth[a] - g.depth[b]) > step_per_metre * std::min(g.depth[a], g.depth[b]);
}

// Marks every pixel within `radius` pixels (Chebyshev) of a marked one: a row pass, then a
// column pass.
std::vector<uint8_t> grown(const std::vector<uint8_t>& mask, int width, int height, int radius) {
  std::vector<uint8_t> rows(mask.size(), 0), out(mask.size(), 0);
  const auto at = [width](int u, int v) { return static_cast<std::size_t>(v) * width + u; };
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      if (!mask[at(u, v)]) continue;
      for (int x = std::max(0, u - radius); x <= std::min(width - 1, u + radius); ++x) rows[at(x, v)] = 1;
    }
  }
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      if (!rows[at(u, v)]) continue;
      for (int y = std::max(0, v - radius); y <= std::min(height - 1, v + radius); ++y) out[at(u, y)] = 1;
    }
  }
  return out;
}

// Pixels with an 8-neighbour across a depth edge, and those within `grow` pixels of them (whose
// blurred view reaches across the edge), row-major.
std::vector<std::size_t> edgePixels(const SensorGeometry& g, double focal_length, int grow) {
  const float step_per_metre = static_cast<float>(kEdgeStepFootprints / focal_length);
  std::vector<uint8_t> edge(static_cast<std::size_t>(g.width) * g.height, 0);
  for (int v = 0; v < g.height; ++v) {
    for (int u = 0; u < g.width; ++u) {
      const std::size_t i = g.index(u, v);
      // Each pair once: the neighbours to the right and below; both ends are marked.
      for (const auto& [du, dv] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
        const int nu = u + du, nv = v + dv;
        if (nu < 0 || nu >= g.width || nv >= g.height) continue;
        const std::size_t j = g.index(nu, nv);
        if (differ(g, i, j, step_per_metre)) edge[i] = edge[j] = 1;
      }
    }
  }
  if (grow > 0) edge = grown(edge, g.width, g.height, grow);
  std::vector<std::size_t> pixels;
  for (std::size_t i = 0; i < edge.size(); ++i) {
    if (edge[i]) pixels.push_back(i);
  }
  return pixels;
}

// Where a pixel gathers its light, along one image axis: its area [-0.5, 0.5] seen through a lens
// whose point spread is a Gaussian of `sigma` pixels. The cumulative share of the light that
// comes from offsets below x: box convolved with Gaussian, F(x) = G(x + 0.5) - G(x - 0.5) with
// G(y) = y Phi(y / sigma) + sigma phi(y / sigma).
double gatheredShare(double x, double sigma) {
  if (sigma <= 0.0) return std::clamp(x + 0.5, 0.0, 1.0);
  const auto G = [sigma](double y) {
    const double t = y / sigma;
    return y * 0.5 * std::erfc(-t / std::sqrt(2.0)) + sigma * std::exp(-0.5 * t * t) * kInverseSqrtTwoPi;
  };
  return G(x + 0.5) - G(x - 0.5);
}

// k offsets that split the pixel's light along one axis into k equal shares, each at the middle
// of its share (stratified quantiles): equally weighted samples of what the pixel sees. Without
// blur, the centres of k equal strips of the pixel.
std::vector<double> sampleOffsets(int k, double sigma) {
  std::vector<double> offsets;
  const double reach = 0.5 + 8.0 * sigma;
  for (int s = 0; s < k; ++s) {
    const double share = (s + 0.5) / k;
    double lo = -reach, hi = reach;
    for (int step = 0; step < 60; ++step) {  // bisection to far below a thousandth of a pixel
      const double mid = 0.5 * (lo + hi);
      (gatheredShare(mid, sigma) < share ? lo : hi) = mid;
    }
    offsets.push_back(0.5 * (lo + hi));
  }
  return offsets;
}

// The k x k sample points of each pixel, the points of one pixel consecutive.
std::vector<Eigen::Vector2d> samplePoints(const std::vector<std::size_t>& pixels, int width,
                                          const std::vector<double>& offsets) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(pixels.size() * offsets.size() * offsets.size());
  for (const std::size_t i : pixels) {
    const double u = static_cast<double>(i % static_cast<std::size_t>(width));
    const double v = static_cast<double>(i / static_cast<std::size_t>(width));
    for (const double dy : offsets) {
      for (const double dx : offsets) points.emplace_back(u + dx, v + dy);
    }
  }
  return points;
}

// The samples of one pixel that see one surface: the same object, lit or not alike, at depths
// within an edge step of the first of them.
struct SurfaceGroup {
  int32_t object_index = -1;
  uint8_t lit = 0;
  float depth = 0.0f;
  std::vector<std::size_t> samples;
};

std::vector<SurfaceGroup> surfaceGroups(const SensorGeometry& samples, std::size_t first, std::size_t count,
                                        float step_per_metre) {
  std::vector<SurfaceGroup> groups;
  for (std::size_t s = first; s < first + count; ++s) {
    if (samples.object_index[s] < 0) continue;  // sees nothing: gathers no light
    const auto same = [&](const SurfaceGroup& g) {
      return g.object_index == samples.object_index[s] && g.lit == samples.lit[s] &&
             std::fabs(g.depth - samples.depth[s]) <= step_per_metre * std::min(g.depth, samples.depth[s]);
    };
    auto group = std::find_if(groups.begin(), groups.end(), same);
    if (group == groups.end()) {
      groups.push_back({samples.object_index[s], samples.lit[s], samples.depth[s], {}});
      group = groups.end() - 1;
    }
    group->samples.push_back(s);
  }
  return groups;
}

// One surface as the pixel sees it: its samples' light averaged, their spread over the projector
// image added to the projector's blur (the pixel sees that stretch of the pattern).
SeenSurface seenSurface(const SurfaceGroup& group, const std::vector<PixelLighting>& light, std::size_t per_pixel) {
  const double n = static_cast<double>(group.samples.size());
  double x = 0, y = 0, xx = 0, yy = 0, blur2 = 0, direct = 0, ambient = 0, global = 0;
  for (const std::size_t s : group.samples) {
    const PixelLighting& l = light[s];
    x += l.projector_x;
    y += l.projector_y;
    xx += static_cast<double>(l.projector_x) * l.projector_x;
    yy += static_cast<double>(l.projector_y) * l.projector_y;
    blur2 += static_cast<double>(l.blur_sigma) * l.blur_sigma;
    direct += l.direct;
    ambient += l.ambient;
    global += l.global;
  }
  x /= n;
  y /= n;
  const double spread = std::max(0.0, 0.5 * (xx / n - x * x + yy / n - y * y));
  SeenSurface seen;
  seen.light.projector_x = static_cast<float>(x);
  seen.light.projector_y = static_cast<float>(y);
  seen.light.blur_sigma = static_cast<float>(std::sqrt(blur2 / n + spread));
  seen.light.direct = static_cast<float>(direct / n);
  seen.light.ambient = static_cast<float>(ambient / n);
  seen.light.global = static_cast<float>(global / n);
  seen.share = static_cast<float>(n / static_cast<double>(per_pixel));
  return seen;
}

}  // namespace

MixedPixels computeMixedPixels(const io::RigCalibration& rig, const RayCaster& scene, const SensorGeometry& geometry,
                               const PhotometryParams& photometry, const AlbedoFunction& albedo,
                               const SensorGeometryParams& geometry_params) {
  photometry.validate();
  MixedPixels mixed;
  const int k = photometry.mixed_pixel_samples;
  if (k <= 1) return mixed;
  const std::vector<double> offsets = sampleOffsets(k, photometry.camera_blur_sigma);
  // A pixel whose farthest sample lies beyond its own area also needs tracing when an edge runs
  // that far from it.
  const int grow = static_cast<int>(std::ceil(std::max(0.0, std::fabs(offsets.front()) - 0.5)));
  const std::vector<std::size_t> candidates = edgePixels(geometry, rig.camera.fx, grow);
  const auto per_pixel = static_cast<std::size_t>(k * k);
  const SensorGeometry samples = computeSensorGeometryAt(rig, scene, samplePoints(candidates, geometry.width, offsets),
                                                         static_cast<int>(per_pixel), geometry_params);
  const std::vector<PixelLighting> light = computePixelLighting(samples, rig, photometry, albedo);
  const float step_per_metre = static_cast<float>(kEdgeStepFootprints / rig.camera.fx);
  mixed.first.push_back(0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::vector<SurfaceGroup> groups = surfaceGroups(samples, c * per_pixel, per_pixel, step_per_metre);
    // A pixel that sees one whole surface is not mixed: its centre ray stands for it.
    if (groups.size() == 1 && groups.front().samples.size() == per_pixel) continue;
    mixed.pixel.push_back(candidates[c]);
    for (const SurfaceGroup& group : groups) mixed.surfaces.push_back(seenSurface(group, light, per_pixel));
    mixed.first.push_back(mixed.surfaces.size());
  }
  if (mixed.pixel.empty()) mixed.first.clear();
  return mixed;
}

}  // namespace binpick::simulation::detail
