// RayCaster: construction, accessors and the ray queries.
#include "binpick/simulation/ray_caster.hpp"

#include <string>

#include "binpick/core/error.hpp"
#include "embree_rays.hpp"
#include "ray_caster_impl.hpp"

namespace binpick::simulation {
namespace {

// Closest hit in `scene`; `alone_index` >= 0 names the object of a single-object scene.
RayHit intersect(const detail::CasterScene& data, RTCScene scene, int alone_index, const Ray& ray) {
  const detail::PreparedRay prepared = detail::prepareRay(ray);
  if (!prepared.valid) return {};
  RTCRayHit query = detail::unhitQuery(prepared.ray);  // 16-byte aligned, as Embree needs
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, &query);
  return detail::resolveHit(data, query, alone_index, ray, prepared.unit_direction);
}

bool anyHit(RTCScene scene, const Ray& ray) {
  detail::PreparedRay prepared = detail::prepareRay(ray);
  if (!prepared.valid) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, &prepared.ray);
  return detail::wasOccluded(prepared.ray);
}

}  // namespace

void RayCaster::Impl::requireIndex(int object_index, const char* caller) const {
  const std::size_t size = data.objects.size();
  if (object_index < 0 || object_index >= static_cast<int>(size)) {
    throw core::Error(std::string("RayCaster::") + caller + ": object index " + std::to_string(object_index) +
                      " is outside [0, " + std::to_string(size) + ")");
  }
}

RayCaster::RayCaster(const std::vector<RenderObject>& objects)
    : impl_(std::make_unique<Impl>(Impl{detail::buildCasterScene(objects)})) {}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&& other) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&& other) noexcept = default;

int RayCaster::objectCount() const { return impl_ ? static_cast<int>(impl_->data.objects.size()) : 0; }

int32_t RayCaster::objectId(int object_index) const {
  if (!impl_) throw core::Error("RayCaster::objectId: the caster was moved from");
  impl_->requireIndex(object_index, "objectId");
  return impl_->data.objects[object_index].id;
}

const Eigen::Isometry3d& RayCaster::objectPose(int object_index) const {
  if (!impl_) throw core::Error("RayCaster::objectPose: the caster was moved from");
  impl_->requireIndex(object_index, "objectPose");
  return impl_->data.objects[object_index].T_camera_object;
}

Eigen::AlignedBox3d RayCaster::objectBounds(int object_index) const {
  if (!impl_) throw core::Error("RayCaster::objectBounds: the caster was moved from");
  impl_->requireIndex(object_index, "objectBounds");
  return impl_->data.objects[object_index].bounds;
}

RayHit RayCaster::closestHit(const Ray& ray) const {
  if (!impl_) return {};
  return intersect(impl_->data, impl_->data.scene.get(), -1, ray);
}

bool RayCaster::occluded(const Ray& ray) const { return impl_ && anyHit(impl_->data.scene.get(), ray); }

RayHit RayCaster::closestHitAlone(int object_index, const Ray& ray) const {
  if (!impl_) throw core::Error("RayCaster::closestHitAlone: the caster was moved from");
  impl_->requireIndex(object_index, "closestHitAlone");
  return intersect(impl_->data, impl_->data.alone_scenes[object_index].get(), object_index, ray);
}

bool RayCaster::occludedAlone(int object_index, const Ray& ray) const {
  if (!impl_) throw core::Error("RayCaster::occludedAlone: the caster was moved from");
  impl_->requireIndex(object_index, "occludedAlone");
  return anyHit(impl_->data.alone_scenes[object_index].get(), ray);
}

}  // namespace binpick::simulation
