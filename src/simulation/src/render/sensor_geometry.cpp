// computeSensorGeometry: one camera ray per pixel, then the projector's view of the point hit.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "projector_view.hpp"

namespace binpick::simulation {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Every buffer sized for the image and set to "nothing hit". Filling ~90 MB (at 1280 x 1024) is
// mostly first-touch page faults: the buffers are filled by several threads at once.
SensorGeometry emptyGeometry(int width, int height, int threads) {
  SensorGeometry g;
  g.width = width;
  g.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  const Eigen::Vector3f nan3 = Eigen::Vector3f::Constant(kNaN);
  const std::array<std::function<void()>, 12> fills = {
      [&] { g.point.assign(n, nan3); },
      [&] { g.normal.assign(n, nan3); },
      [&] { g.object_point.assign(n, nan3); },
      [&] { g.projector_pixel.assign(n, Eigen::Vector2f::Constant(kNaN)); },
      [&] { g.depth.assign(n, kNaN); },
      [&] { g.object_id.assign(n, -1); },
      [&] { g.object_index.assign(n, -1); },
      [&] { g.camera_cosine.assign(n, kNaN); },
      [&] { g.projector_cosine.assign(n, kNaN); },
      [&] { g.projector_distance.assign(n, kNaN); },
      [&] { g.in_projector_image.assign(n, 0); },
      [&] { g.lit.assign(n, 0); }};
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::size_t k = 0; k < fills.size(); ++k) fills[k]();
  return g;
}

void storeHit(const RayHit& hit, const Eigen::Vector3d& ray_direction, std::size_t i, SensorGeometry& g) {
  g.depth[i] = static_cast<float>(hit.point.z());
  g.point[i] = hit.point.cast<float>();
  g.normal[i] = hit.normal.cast<float>();
  g.object_point[i] = hit.object_point.cast<float>();
  g.object_id[i] = hit.object_id;
  g.object_index[i] = hit.object_index;
  g.camera_cosine[i] = static_cast<float>(-hit.normal.dot(ray_direction));
}

void storeProjectorSample(const detail::ProjectorSample& s, std::size_t i, SensorGeometry& g) {
  g.projector_pixel[i] = s.pixel.cast<float>();
  g.in_projector_image[i] = s.in_image ? 1 : 0;
  g.projector_cosine[i] = static_cast<float>(s.cosine);
  g.projector_distance[i] = static_cast<float>(s.distance);
  g.lit[i] = s.lit ? 1 : 0;
}

// `count` consecutive entries of the result from `first` on: the rays through their image points,
// and then the shadow rays of their lit-able points, each as one batch (neighbouring rays are
// alike, which Embree's packets exploit).
void renderSpan(const io::LensIntrinsics& camera, const detail::ProjectorView& projector, const RayCaster& scene,
                double shadow_ray_offset, const Eigen::Vector2d* image_points, std::size_t first, std::size_t count,
                SensorGeometry& g) {
  std::vector<Ray> rays(count);
  for (std::size_t k = 0; k < count; ++k) rays[k].direction = camera.rayThroughPixel(image_points[k]);
  const std::vector<RayHit> hits = scene.closestHits(rays);
  const std::vector<detail::ProjectorSample> samples = detail::lightHits(projector, hits, scene, -1, shadow_ray_offset);
  for (std::size_t k = 0; k < count; ++k) {
    if (!hits[k].hit()) continue;
    storeHit(hits[k], rays[k].direction, first + k, g);
    storeProjectorSample(samples[k], first + k, g);
  }
}

// Sub-pixel samples go to the caster in spans of this many: a few rows' worth.
constexpr std::size_t kSampleSpan = 1024;

}  // namespace

SensorGeometry computeSensorGeometry(const io::RigCalibration& rig, const RayCaster& scene,
                                     const SensorGeometryParams& params) {
  rig.validate();
  params.validate();
  const int threads = core::resolveThreadCount(params.threads);
  SensorGeometry g = emptyGeometry(rig.camera.width, rig.camera.height, threads);
  const detail::ProjectorView projector(rig);
  // Each row is traced the same way whichever thread takes it, so the split among threads
  // cannot change the result; dynamic scheduling evens out rows that miss everything.
#pragma omp parallel for num_threads(threads) schedule(dynamic, 2)
  for (int v = 0; v < rig.camera.height; ++v) {
    std::vector<Eigen::Vector2d> centres(rig.camera.width);
    for (int u = 0; u < rig.camera.width; ++u) centres[u] = Eigen::Vector2d(u, v);
    renderSpan(rig.camera, projector, scene, params.shadow_ray_offset, centres.data(), g.index(0, v), centres.size(), g);
  }
  return g;
}

SensorGeometry computeSensorGeometryAt(const io::RigCalibration& rig, const RayCaster& scene,
                                       const std::vector<Eigen::Vector2d>& image_points, int width,
                                       const SensorGeometryParams& params) {
  rig.validate();
  params.validate();
  if (width <= 0 || image_points.size() % static_cast<std::size_t>(width) != 0) {
    throw core::Error("computeSensorGeometryAt: " + std::to_string(image_points.size()) +
                      " image points do not make rows of " + std::to_string(width));
  }
  const int threads = core::resolveThreadCount(params.threads);
  const int height = static_cast<int>(image_points.size() / static_cast<std::size_t>(width));
  SensorGeometry g = emptyGeometry(width, height, threads);
  const detail::ProjectorView projector(rig);
  const auto spans = static_cast<std::ptrdiff_t>((image_points.size() + kSampleSpan - 1) / kSampleSpan);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::ptrdiff_t s = 0; s < spans; ++s) {
    const std::size_t first = static_cast<std::size_t>(s) * kSampleSpan;
    const std::size_t count = std::min(kSampleSpan, image_points.size() - first);
    renderSpan(rig.camera, projector, scene, params.shadow_ray_offset, &image_points[first], first, count, g);
  }
  return g;
}

}  // namespace binpick::simulation

// SensorGeometryParams::validate: every field checked, the message names the first bad one.
namespace binpick::simulation {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "SensorGeometryParams", field, rule, value);
}

constexpr int kMaxThreads = 1024;
// An offset this large would visibly move shadow edges; anything beyond it is a unit mistake.
constexpr double kMaxShadowRayOffset = 0.01;

}  // namespace

void SensorGeometryParams::validate() const {
  require(threads >= 0 && threads <= kMaxThreads, "threads", "in [0, 1024]", threads);
  require(std::isfinite(shadow_ray_offset) && shadow_ray_offset >= 0.0 && shadow_ray_offset <= kMaxShadowRayOffset,
          "shadow_ray_offset", "in [0, 0.01] metres", shadow_ray_offset);
}

}  // namespace binpick::simulation
