#pragma once
// Turns Embree's float hit into an exact one. Internal to binpick::simulation. Pure: thread-safe.
#include <Eigen/Core>

#include "binpick/io/point_cloud.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "ray_caster_impl.hpp"

namespace binpick::simulation::detail {

// The hit of a ray (unit `direction`) with triangle `triangle` of a placed object, recomputed
// in double on the mesh's own vertices at the object's pose: Embree traces a float copy in the
// camera frame, whose distance `t_embree` is only good to ~1e-7 relative. Falls back to
// `t_embree` when the ray grazes the triangle's plane too closely for the recomputation.
RayHit refineHit(const PlacedObject& object, const io::TriangleMesh& mesh, int object_index, int triangle,
                 const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_embree);

}  // namespace binpick::simulation::detail
