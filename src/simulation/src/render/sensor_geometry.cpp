// computeSensorGeometry: one camera ray per pixel, then the projector's view of the point hit.
#include <array>
#include <cmath>
#include <functional>
#include <limits>

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

// One image row: its rays, and then the shadow rays of its lit-able points, each as one batch
// (neighbouring rays are alike, which Embree's packets exploit).
void renderRow(const io::LensIntrinsics& camera, const detail::ProjectorView& projector, const RayCaster& scene,
               double shadow_ray_offset, int v, SensorGeometry& g) {
  std::vector<Ray> rays(camera.width);
  for (int u = 0; u < camera.width; ++u) {
    rays[u].direction = camera.rayThroughPixel(Eigen::Vector2d(u, v));
  }
  const std::vector<RayHit> hits = scene.closestHits(rays);
  const std::vector<detail::ProjectorSample> samples = detail::lightHits(projector, hits, scene, -1, shadow_ray_offset);
  for (int u = 0; u < camera.width; ++u) {
    if (!hits[u].hit()) continue;
    const std::size_t i = g.index(u, v);
    storeHit(hits[u], rays[u].direction, i, g);
    storeProjectorSample(samples[u], i, g);
  }
}

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
    renderRow(rig.camera, projector, scene, params.shadow_ray_offset, v, g);
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
