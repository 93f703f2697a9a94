// refineHit: the ray-plane intersection of the triangle hit, in double.
#include "hit_refinement.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::simulation::detail {
namespace {

// Below this |cos| between the ray and the plane, the double recomputation is no better than
// Embree's own distance.
constexpr double kGrazingCosine = 1e-6;
// The two distances can only differ by float rounding; a larger gap means the recomputation is
// not to be trusted (it never should be), and Embree's value is kept.
constexpr double kMaxRelativeCorrection = 1e-3;

}  // namespace

RayHit refineHit(const PlacedObject& object, const io::TriangleMesh& mesh, int object_index, int triangle,
                 const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_embree) {
  const Eigen::Vector3i& corners = mesh.triangles[triangle];
  const Eigen::Vector3d a = mesh.vertices[corners[0]].cast<double>();
  const Eigen::Vector3d b = mesh.vertices[corners[1]].cast<double>();
  const Eigen::Vector3d c = mesh.vertices[corners[2]].cast<double>();
  const Eigen::Vector3d local_normal = (b - a).cross(c - a).normalized();

  // Work in the object frame, where the vertices are exact.
  const Eigen::Vector3d local_origin = object.T_object_camera * origin;
  const Eigen::Vector3d local_direction = object.T_object_camera.linear() * direction;
  double t = t_embree;
  const double cosine = local_normal.dot(local_direction);
  if (std::abs(cosine) > kGrazingCosine) {
    const double exact = local_normal.dot(a - local_origin) / cosine;
    if (std::abs(exact - t_embree) <= kMaxRelativeCorrection * std::max(1.0, t_embree)) t = exact;
  }

  RayHit hit;
  hit.t = t;
  hit.point = origin + t * direction;
  hit.object_point = local_origin + t * local_direction;
  hit.normal = object.T_camera_object.linear() * local_normal;
  hit.object_id = object.id;
  hit.object_index = object_index;
  hit.triangle = triangle;
  return hit;
}

}  // namespace binpick::simulation::detail
