// prepareRay, unhitQuery, resolveHit: the RayCaster's rays and hits in Embree's terms.
#include "embree_rays.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hit_refinement.hpp"

namespace binpick::simulation::detail {
namespace {

RTCRay embreeRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, float t_min, float t_max) {
  RTCRay out;
  out.org_x = static_cast<float>(origin.x());
  out.org_y = static_cast<float>(origin.y());
  out.org_z = static_cast<float>(origin.z());
  out.dir_x = static_cast<float>(direction.x());
  out.dir_y = static_cast<float>(direction.y());
  out.dir_z = static_cast<float>(direction.z());
  out.tnear = t_min;
  out.tfar = t_max;
  out.time = 0.0f;
  out.mask = std::numeric_limits<unsigned>::max();
  out.id = 0;
  out.flags = 0;
  return out;
}

}  // namespace

PreparedRay prepareRay(const Ray& ray) {
  PreparedRay out;
  // Embree skips a ray whose range is empty: the stand-in for every invalid ray.
  out.ray = embreeRay(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0f, 0.0f);
  const double length = ray.direction.norm();
  if (!ray.origin.allFinite() || !std::isfinite(length) || length <= 0.0) return out;
  if (std::isnan(ray.t_min) || std::isnan(ray.t_max)) return out;
  // Embree searches [0, inf] at most: nothing behind the origin.
  const float t_min = static_cast<float>(std::max(ray.t_min, 0.0));
  const float t_max = static_cast<float>(ray.t_max);  // beyond float range: +inf
  if (!std::isfinite(t_min) || !(t_min <= t_max)) return out;
  out.unit_direction = ray.direction / length;
  out.ray = embreeRay(ray.origin, out.unit_direction, t_min, t_max);
  out.valid = true;
  return out;
}

RTCRayHit unhitQuery(const RTCRay& ray) {
  RTCRayHit query;
  query.ray = ray;
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.primID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return query;
}

RayHit resolveHit(const CasterScene& scene, const RTCRayHit& query, int alone_index, const Ray& ray,
                  const Eigen::Vector3d& unit_direction) {
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  const int index = alone_index >= 0 ? alone_index : static_cast<int>(query.hit.geomID);
  const PlacedObject& object = scene.objects[index];
  return refineHit(object, scene.meshes[object.mesh], index, static_cast<int>(query.hit.primID), ray.origin,
                   unit_direction, query.ray.tfar);
}

}  // namespace binpick::simulation::detail
