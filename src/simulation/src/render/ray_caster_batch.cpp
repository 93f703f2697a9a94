// RayCaster's batch queries: Embree ray streams, traced as coherent packets.
#include <algorithm>
#include <array>

#include "binpick/core/error.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "embree_rays.hpp"
#include "ray_caster_impl.hpp"

namespace binpick::simulation {
namespace {

// Batches go to Embree in chunks of this many rays, held on the stack: large enough for
// Embree's packets, small enough to stay in cache and to need no allocation.
constexpr std::size_t kChunk = 256;

RTCIntersectContext coherentContext() {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return context;
}

std::vector<RayHit> intersectAll(const detail::CasterScene& data, RTCScene scene, int alone_index,
                                 const std::vector<Ray>& rays) {
  std::vector<RayHit> hits(rays.size());
  std::array<RTCRayHit, kChunk> queries;
  std::array<Eigen::Vector3d, kChunk> directions;
  std::array<bool, kChunk> valid;
  for (std::size_t begin = 0; begin < rays.size(); begin += kChunk) {
    const std::size_t count = std::min(kChunk, rays.size() - begin);
    for (std::size_t k = 0; k < count; ++k) {
      const detail::PreparedRay prepared = detail::prepareRay(rays[begin + k]);
      queries[k] = detail::unhitQuery(prepared.ray);
      directions[k] = prepared.unit_direction;
      valid[k] = prepared.valid;
    }
    RTCIntersectContext context = coherentContext();
    rtcIntersect1M(scene, &context, queries.data(), static_cast<unsigned>(count), sizeof(RTCRayHit));
    for (std::size_t k = 0; k < count; ++k) {
      if (!valid[k]) continue;
      hits[begin + k] = detail::resolveHit(data, queries[k], alone_index, rays[begin + k], directions[k]);
    }
  }
  return hits;
}

std::vector<uint8_t> occludedAll(RTCScene scene, const std::vector<Ray>& rays) {
  std::vector<uint8_t> occluded(rays.size(), 0);
  std::array<RTCRay, kChunk> queries;
  for (std::size_t begin = 0; begin < rays.size(); begin += kChunk) {
    const std::size_t count = std::min(kChunk, rays.size() - begin);
    // An invalid ray is inactive (tnear > tfar): Embree leaves it alone and it reads as clear.
    for (std::size_t k = 0; k < count; ++k) queries[k] = detail::prepareRay(rays[begin + k]).ray;
    RTCIntersectContext context = coherentContext();
    rtcOccluded1M(scene, &context, queries.data(), static_cast<unsigned>(count), sizeof(RTCRay));
    for (std::size_t k = 0; k < count; ++k) {
      occluded[begin + k] = detail::wasOccluded(queries[k]) ? 1 : 0;
    }
  }
  return occluded;
}

}  // namespace

std::vector<RayHit> RayCaster::closestHits(const std::vector<Ray>& rays) const {
  if (!impl_) return std::vector<RayHit>(rays.size());
  return intersectAll(impl_->data, impl_->data.scene.get(), -1, rays);
}

std::vector<uint8_t> RayCaster::occludedEach(const std::vector<Ray>& rays) const {
  if (!impl_) return std::vector<uint8_t>(rays.size(), 0);
  return occludedAll(impl_->data.scene.get(), rays);
}

std::vector<RayHit> RayCaster::closestHitsAlone(int object_index, const std::vector<Ray>& rays) const {
  if (!impl_) throw core::Error("RayCaster::closestHitsAlone: the caster was moved from");
  impl_->requireIndex(object_index, "closestHitsAlone");
  return intersectAll(impl_->data, impl_->data.alone_scenes[object_index].get(), object_index, rays);
}

std::vector<uint8_t> RayCaster::occludedEachAlone(int object_index, const std::vector<Ray>& rays) const {
  if (!impl_) throw core::Error("RayCaster::occludedEachAlone: the caster was moved from");
  impl_->requireIndex(object_index, "occludedEachAlone");
  return occludedAll(impl_->data.alone_scenes[object_index].get(), rays);
}

}  // namespace binpick::simulation
