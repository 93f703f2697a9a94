#include "binpick/cell/seal_check.hpp"

#include <cmath>
#include <string>

#include "binpick/io/error.hpp"

namespace binpick::cell {
namespace {

// Samples over the disc: its centre and rings at a third, two thirds and the whole checked
// radius, denser outwards where edges cross first. About 1 mm apart on a 10 mm cup.
constexpr int kRings = 3;
constexpr int kSamplesPerRing[kRings] = {8, 16, 24};

}  // namespace

void SealCheckParams::validate() const {
  const std::string owner = "picking.seal_check";
  requireField(std::isfinite(rim_margin) && rim_margin >= 0, owner, "rim_margin", ">= 0", rim_margin);
  requireField(std::isfinite(noise) && noise >= 0, owner, "noise", ">= 0", noise);
  requireField(min_seen_share >= 0 && min_seen_share <= 1, owner, "min_seen_share", "in [0, 1]", min_seen_share);
}

MeasuredSurface::MeasuredSurface(const PointCloud& cloud, const LensIntrinsics& camera,
                                 const Eigen::Isometry3d& T_base_camera)
    : cloud_(cloud), camera_(camera), T_camera_base_(T_base_camera.inverse()) {
  camera.validate("camera");
  if (cloud.width != camera.width || cloud.height != camera.height ||
      cloud.points.size() != static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height)) {
    throw Error("seal check: the cloud (" + std::to_string(cloud.width) + " x " + std::to_string(cloud.height) +
                ") is not organized as the camera's image (" + std::to_string(camera.width) + " x " +
                std::to_string(camera.height) + ")");
  }
}

SealCheck MeasuredSurface::check(const Eigen::Isometry3d& T_base_grasp, double radius, double tolerance,
                                 const SealCheckParams& params) const {
  const Eigen::Isometry3d T_camera_grasp = T_camera_base_ * T_base_grasp;
  const Eigen::Vector3d origin = T_camera_grasp.translation();
  const Eigen::Vector3d normal = T_camera_grasp.linear().col(2);
  const double checked_radius = radius + params.rim_margin;
  const double allowed = tolerance + params.noise;
  int samples = 0, seen = 0;
  SealCheck result;
  bool flat = true;
  const auto sample = [&](const Eigen::Vector3d& in_grasp) {
    ++samples;
    const Eigen::Vector3d point = T_camera_grasp * in_grasp;
    if (!(point.z() > 0.0)) return;
    const Eigen::Vector2d pixel = camera_.project(point);
    const long u = std::lround(pixel.x()), v = std::lround(pixel.y());
    if (!(u >= 0 && v >= 0 && u < camera_.width && v < camera_.height)) return;
    const Eigen::Vector3f& measured = cloud_.points[static_cast<std::size_t>(v) * camera_.width + u];
    if (!measured.allFinite()) return;
    ++seen;
    // Distance of the measured point from the grasp plane: along the approach, positive beyond it.
    const double deviation = std::abs((measured.cast<double>() - origin).dot(normal));
    result.worst_deviation = std::max(result.worst_deviation, deviation);
    flat = flat && deviation <= allowed;
  };
  sample(Eigen::Vector3d::Zero());
  for (int ring = 0; ring < kRings; ++ring) {
    const double r = checked_radius * (ring + 1) / kRings;
    for (int k = 0; k < kSamplesPerRing[ring]; ++k) {
      const double angle = 2.0 * M_PI * k / kSamplesPerRing[ring];
      sample({r * std::cos(angle), r * std::sin(angle), 0.0});
    }
  }
  result.seen_share = static_cast<double>(seen) / samples;
  result.seals = flat && result.seen_share >= params.min_seen_share;
  return result;
}

}  // namespace binpick::cell
