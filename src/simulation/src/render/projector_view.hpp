#pragma once
// How surface points stand towards the projector of the rig: where they land in the projector
// image, and whether, at what angle and from how far, projector light reaches them. Internal to
// binpick::simulation. Immutable once built: thread-safe.
#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/ray_caster.hpp"

namespace binpick::simulation::detail {

struct ProjectorSample {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d pixel = Eigen::Vector2d::Constant(kNaN);  // NaN behind the projector
  bool in_image = false;
  double cosine = kNaN;    // normal . (unit vector from the point to the projector centre)
  double distance = kNaN;  // metres to the projector centre
  bool lit = false;        // in the image, facing the projector, nothing in between

  // Light can reach the point unless something is in the way.
  bool exposed() const { return in_image && cosine > 0.0; }
};

class ProjectorView {
 public:
  explicit ProjectorView(const io::RigCalibration& rig);

  // Everything but the shadow test (lit stays false); `point` and unit outward `normal` in the
  // camera frame.
  ProjectorSample locate(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const;
  // From `offset` metres off the surface (so that it cannot hit the triangle it leaves) to the
  // projector centre: the projector itself is not part of the scene.
  Ray shadowRay(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double offset) const;

 private:
  bool inImage(const Eigen::Vector3d& point_projector, Eigen::Vector2d* pixel) const;

  io::LensIntrinsics lens_;
  Eigen::Isometry3d T_projector_camera_;
  Eigen::Vector3d centre_camera_;     // the projector's centre of projection, camera frame
  Eigen::AlignedBox2d field_bounds_;  // normalised directions the projector can light
};

// The projector samples of `hits` (a miss gives the default sample), lit included: shadows are
// cast by the whole scene, or by object `alone_object` only when it is >= 0. The shadow rays of
// the exposed points go to the caster as one batch.
std::vector<ProjectorSample> lightHits(const ProjectorView& projector, const std::vector<RayHit>& hits,
                                       const RayCaster& scene, int alone_object, double shadow_ray_offset);

}  // namespace binpick::simulation::detail
