// ProjectorView and lightHits: projection into the projector and the shadow test.
#include "projector_view.hpp"

#include <cmath>

#include "lens_bounds.hpp"

namespace binpick::simulation::detail {
namespace {

// Margin on the projector's field of view for telling real image points from points that the
// distortion polynomial folds back into the image from far outside it.
constexpr double kFieldMargin = 0.05;

}  // namespace

ProjectorView::ProjectorView(const io::RigCalibration& rig)
    : lens_(rig.projector),
      T_projector_camera_(rig.T_projector_camera),
      centre_camera_(rig.T_projector_camera.inverse(Eigen::Isometry).translation()),
      field_bounds_(normalisedImageBounds(rig.projector, kFieldMargin)) {}

bool ProjectorView::inImage(const Eigen::Vector3d& point_projector, Eigen::Vector2d* pixel) const {
  if (!(point_projector.z() > 0.0)) return false;
  *pixel = lens_.project(point_projector);
  const Eigen::Vector2d direction = point_projector.head<2>() / point_projector.z();
  return field_bounds_.contains(direction) && pixel->x() >= -0.5 && pixel->x() < lens_.width - 0.5 &&
         pixel->y() >= -0.5 && pixel->y() < lens_.height - 0.5;
}

ProjectorSample ProjectorView::locate(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const {
  ProjectorSample out;
  out.in_image = inImage(T_projector_camera_ * point, &out.pixel);
  const Eigen::Vector3d to_projector = centre_camera_ - point;
  out.distance = to_projector.norm();
  if (out.distance > 0.0) out.cosine = normal.dot(to_projector / out.distance);
  return out;
}

Ray ProjectorView::shadowRay(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double offset) const {
  Ray ray;
  ray.origin = point + offset * normal;
  ray.direction = centre_camera_ - ray.origin;
  ray.t_max = ray.direction.norm();
  return ray;
}

std::vector<ProjectorSample> lightHits(const ProjectorView& projector, const std::vector<RayHit>& hits,
                                       const RayCaster& scene, int alone_object, double shadow_ray_offset) {
  std::vector<ProjectorSample> samples(hits.size());
  std::vector<std::size_t> exposed;
  std::vector<Ray> shadow_rays;
  exposed.reserve(hits.size());
  shadow_rays.reserve(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (!hits[i].hit()) continue;
    samples[i] = projector.locate(hits[i].point, hits[i].normal);
    if (!samples[i].exposed()) continue;
    exposed.push_back(i);
    shadow_rays.push_back(projector.shadowRay(hits[i].point, hits[i].normal, shadow_ray_offset));
  }
  const std::vector<uint8_t> shadowed =
      alone_object >= 0 ? scene.occludedEachAlone(alone_object, shadow_rays) : scene.occludedEach(shadow_rays);
  for (std::size_t k = 0; k < exposed.size(); ++k) samples[exposed[k]].lit = !shadowed[k];
  return samples;
}

}  // namespace binpick::simulation::detail
