#pragma once
// Conversions between the RayCaster's rays and hits and Embree's. Internal to
// binpick::simulation. Pure functions: thread-safe.
#include <embree3/rtcore.h>

#include <Eigen/Core>

#include "binpick/simulation/ray_caster.hpp"
#include "ray_caster_impl.hpp"

namespace binpick::simulation::detail {

// A ray ready for Embree. An invalid ray (non-finite or zero direction, non-finite origin, NaN
// limits, an empty range) becomes an inactive Embree ray (tnear > tfar), which never hits.
struct PreparedRay {
  RTCRay ray;
  Eigen::Vector3d unit_direction = Eigen::Vector3d::Zero();
  bool valid = false;
};
PreparedRay prepareRay(const Ray& ray);

// A query slot with no hit recorded yet.
RTCRayHit unhitQuery(const RTCRay& ray);

// The hit Embree recorded in `query` (traced for `ray`), refined; a miss if none. In a
// single-object scene, `alone_index` names the object; otherwise it is -1.
RayHit resolveHit(const CasterScene& scene, const RTCRayHit& query, int alone_index, const Ray& ray,
                  const Eigen::Vector3d& unit_direction);

// Embree marks an occluded ray by setting its tfar to -inf.
inline bool wasOccluded(const RTCRay& ray) { return ray.tfar < 0.0f; }

}  // namespace binpick::simulation::detail
