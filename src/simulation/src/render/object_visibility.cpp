// computeObjectVisibility: measured pixels per object in the pile, and alone at the same pose.
#include "render/object_visibility.hpp"

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"
#include "lens_bounds.hpp"
#include "projector_view.hpp"

namespace binpick::simulation {
namespace {

// Margin on the camera's field of view when bounding an object's footprint: pixels are only
// ever searched inside the image, so this merely keeps the distortion map one-to-one.
constexpr double kFieldMargin = 0.05;

void requireMatchingGeometry(const io::RigCalibration& rig, const SensorGeometry& geometry) {
  const std::size_t n = static_cast<std::size_t>(rig.camera.width) * rig.camera.height;
  if (geometry.width != rig.camera.width || geometry.height != rig.camera.height || geometry.object_index.size() != n ||
      geometry.lit.size() != n || geometry.in_projector_image.size() != n || geometry.projector_cosine.size() != n) {
    throw core::Error("computeObjectVisibility: the sensor geometry does not match the camera size");
  }
}

std::vector<int> countVisibleLit(const SensorGeometry& geometry, int objects) {
  std::vector<int> counts(objects, 0);
  for (std::size_t i = 0; i < geometry.object_index.size(); ++i) {
    const int index = geometry.object_index[i];
    if (index >= 0 && index < objects && geometry.lit[i]) ++counts[index];
  }
  return counts;
}

// Where the full scene already sees the object, the alone scene sees the same point (the
// nearest surface along the ray is on the object either way) and the other objects can only
// take light away: a lit pixel stays lit, and one out of the projector image or facing away
// stays dark. Only pixels where the object is hidden, or shadowed by something, are cast again.
enum class AloneAnswer { kLit, kDark, kCastAgain };

AloneAnswer answerFromGeometry(const SensorGeometry& geometry, std::size_t i, int object) {
  if (geometry.object_index[i] != object) return AloneAnswer::kCastAgain;
  if (geometry.lit[i]) return AloneAnswer::kLit;
  const bool exposed = geometry.in_projector_image[i] && geometry.projector_cosine[i] > 0.0f;
  return exposed ? AloneAnswer::kCastAgain : AloneAnswer::kDark;
}

// Pixels of row v within `pixels` that would see `object`, lit, were it alone.
int countAloneLitInRow(const io::RigCalibration& rig, const RayCaster& scene, const detail::ProjectorView& projector,
                       const SensorGeometry& geometry, const detail::PixelRange& pixels, int v, int object,
                       double shadow_ray_offset) {
  int count = 0;
  std::vector<Ray> rays;
  for (int u = pixels.u_begin; u < pixels.u_end; ++u) {
    const AloneAnswer answer = answerFromGeometry(geometry, geometry.index(u, v), object);
    if (answer == AloneAnswer::kLit) ++count;
    if (answer != AloneAnswer::kCastAgain) continue;
    rays.emplace_back();
    rays.back().direction = rig.camera.rayThroughPixel(Eigen::Vector2d(u, v));
  }
  if (rays.empty()) return count;
  const std::vector<RayHit> hits = scene.closestHitsAlone(object, rays);
  for (const auto& sample : detail::lightHits(projector, hits, scene, object, shadow_ray_offset)) {
    if (sample.lit) ++count;
  }
  return count;
}

// One row of one object's projected bounding box.
struct RowTask {
  int object;
  int v;
  detail::PixelRange pixels;
};

std::vector<RowTask> rowTasks(const io::RigCalibration& rig, const RayCaster& scene,
                              const std::vector<int>& object_indices) {
  const Eigen::AlignedBox2d field = detail::normalisedImageBounds(rig.camera, kFieldMargin);
  std::vector<RowTask> tasks;
  std::vector<bool> listed(scene.objectCount(), false);
  for (int object : object_indices) {
    if (listed[object]) continue;  // an object asked for twice is counted once
    listed[object] = true;
    const detail::PixelRange pixels = detail::pixelsSeeing(rig.camera, field, scene.objectBounds(object));
    if (pixels.empty()) continue;
    for (int v = pixels.v_begin; v < pixels.v_end; ++v) tasks.push_back({object, v, pixels});
  }
  return tasks;
}

// Per object of `object_indices`, the pixels that would see it, lit, were it alone.
std::vector<int> countAloneLit(const io::RigCalibration& rig, const RayCaster& scene, const SensorGeometry& geometry,
                               const std::vector<int>& object_indices, const SensorGeometryParams& params) {
  const detail::ProjectorView projector(rig);
  const std::vector<RowTask> tasks = rowTasks(rig, scene, object_indices);
  std::vector<int> row_counts(tasks.size(), 0);
  const int threads = core::resolveThreadCount(params.threads);
  // All objects' rows in one loop: a single barrier, however many objects. Each row is batched
  // the same way whichever thread takes it, so the counts do not depend on the split.
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    const RowTask& task = tasks[k];
    row_counts[k] =
        countAloneLitInRow(rig, scene, projector, geometry, task.pixels, task.v, task.object, params.shadow_ray_offset);
  }
  std::vector<int> per_object(scene.objectCount(), 0);
  for (std::size_t k = 0; k < tasks.size(); ++k) per_object[tasks[k].object] += row_counts[k];
  return per_object;
}

}  // namespace

std::vector<ObjectVisibility> computeObjectVisibilityOf(const io::RigCalibration& rig, const RayCaster& scene,
                                                        const SensorGeometry& geometry,
                                                        const std::vector<int>& object_indices,
                                                        const SensorGeometryParams& params) {
  rig.validate();
  params.validate();
  requireMatchingGeometry(rig, geometry);
  for (int index : object_indices) scene.objectBounds(index);  // throws on a bad index, up front
  const std::vector<int> visible = countVisibleLit(geometry, scene.objectCount());
  const std::vector<int> alone = countAloneLit(rig, scene, geometry, object_indices, params);
  std::vector<ObjectVisibility> result;
  result.reserve(object_indices.size());
  for (int object : object_indices) {
    ObjectVisibility out;
    out.visible_lit_pixels = visible[object];
    out.alone_lit_pixels = alone[object];
    if (out.alone_lit_pixels > 0) {
      out.visible_fraction = static_cast<double>(out.visible_lit_pixels) / out.alone_lit_pixels;
    }
    result.push_back(out);
  }
  return result;
}

std::vector<ObjectVisibility> computeObjectVisibility(const io::RigCalibration& rig, const RayCaster& scene,
                                                      const SensorGeometry& geometry,
                                                      const SensorGeometryParams& params) {
  std::vector<int> all(scene.objectCount());
  for (int i = 0; i < scene.objectCount(); ++i) all[i] = i;
  return computeObjectVisibilityOf(rig, scene, geometry, all, params);
}

}  // namespace binpick::simulation
