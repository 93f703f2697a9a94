#include "binpick/picking/seal_check.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "binpick/core/error.hpp"
#include "rigid.hpp"

namespace binpick::picking {
namespace {

// Samples over the disc: its centre and rings at a third, two thirds and the whole checked
// radius, denser outwards where edges cross first. About 1 mm apart on a 10 mm cup.
constexpr int kRings = 3;
constexpr int kSamplesPerRing[kRings] = {8, 16, 24};
// Pixels searched around an unmeasured sample for the far side of an edge (3: a 7 x 7 window, about 2 mm across).
constexpr long kEdgeSearch = 3;

// The least-squares plane through points given one at a time, kept relative to `origin` (well
// conditioned for points a few millimetres from it): no list of them on the planner's hot path.
class PlaneFit {
 public:
  explicit PlaneFit(const Eigen::Vector3d& origin) : origin_(origin) {}

  void add(const Eigen::Vector3d& point) {
    const Eigen::Vector3d offset = point - origin_;
    ++count_;
    sum_ += offset;
    products_ += offset * offset.transpose();
  }

  int count() const { return count_; }

  // Degrees between `axis` and the plane's normal (the eigenvector of the points' scatter with the
  // smallest eigenvalue), either way round; 90 when fewer than 3 points.
  double normalAngleDeg(const Eigen::Vector3d& axis) const {
    if (count_ < 3) return 90.0;
    const Eigen::Vector3d mean = sum_ / count_;
    const Eigen::Matrix3d scatter = products_ - count_ * mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    const Eigen::Vector3d normal = solver.eigenvectors().col(0);
    return angleDeg(normal.dot(axis) >= 0.0 ? normal : Eigen::Vector3d(-normal), axis);
  }

 private:
  Eigen::Vector3d origin_;
  int count_ = 0;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d products_ = Eigen::Matrix3d::Zero();
};

}  // namespace

void SealCheckParams::validate() const {
  const std::string owner = "picking.seal_check";
  core::requireField(isNonNegative(rim_margin), owner, "rim_margin", ">= 0", rim_margin);
  core::requireField(isNonNegative(noise), owner, "noise", ">= 0", noise);
  core::requireField(min_seen_share >= 0 && min_seen_share <= 1, owner, "min_seen_share", "in [0, 1]", min_seen_share);
  core::requireField(isNonNegative(max_shift), owner, "max_shift", ">= 0", max_shift);
  core::requireField(isPositive(shift_step), owner, "shift_step", "> 0", shift_step);
  core::requireField(max_angle_deg > 0 && max_angle_deg <= 90, owner, "max_angle_deg", "in (0, 90]", max_angle_deg);
}

MeasuredSurface::MeasuredSurface(const io::PointCloud& cloud, const io::LensIntrinsics& camera,
                                 const Eigen::Isometry3d& T_base_camera)
    : cloud_(cloud), camera_(camera), T_camera_base_(T_base_camera.inverse()) {
  camera.validate("camera");
  if (cloud.width != camera.width || cloud.height != camera.height ||
      cloud.points.size() != static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height)) {
    throw core::Error("seal check: the cloud (" + std::to_string(cloud.width) + " x " + std::to_string(cloud.height) +
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
  int samples = 0;
  PlaneFit seen_plane(origin);  // the measured samples
  SealCheck result;
  bool flat = true;
  const auto pointAt = [&](long u, long v) -> const Eigen::Vector3f& {
    return cloud_
        .points[static_cast<std::size_t>(v) * static_cast<std::size_t>(camera_.width) + static_cast<std::size_t>(u)];
  };
  const auto offPlaneNear = [&](long u, long v, double limit, const auto& deviation) {
    for (long dv = -kEdgeSearch; dv <= kEdgeSearch; ++dv) {
      for (long du = -kEdgeSearch; du <= kEdgeSearch; ++du) {
        const long x = u + du, y = v + dv;
        if (x < 0 || y < 0 || x >= camera_.width || y >= camera_.height) continue;
        const Eigen::Vector3f& near = pointAt(x, y);
        if (near.allFinite() && deviation(near) > limit) return true;
      }
    }
    return false;
  };
  const auto deviationOf = [&](const Eigen::Vector3f& measured) {
    // Distance of the measured point from the grasp plane, along the approach.
    return std::abs((measured.cast<double>() - origin).dot(normal));
  };
  const auto sample = [&](const Eigen::Vector3d& in_grasp) {
    ++samples;
    const Eigen::Vector3d point = T_camera_grasp * in_grasp;
    if (!(point.z() > 0.0)) return;
    const Eigen::Vector2d pixel = camera_.project(point);
    const long u = std::lround(pixel.x()), v = std::lround(pixel.y());
    if (!(u >= 0 && v >= 0 && u < camera_.width && v < camera_.height)) return;
    const Eigen::Vector3f& measured = pointAt(u, v);
    if (!measured.allFinite()) {
      // Nothing measured here: a dropout inside a face, or the shadow or filtered mixed pixels
      // along a depth edge. Next to an edge a pixel close by measures the other side of it.
      flat = flat && !offPlaneNear(u, v, allowed, deviationOf);
      return;
    }
    seen_plane.add(measured.cast<double>());
    const double deviation = deviationOf(measured);
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
  result.seen_share = static_cast<double>(seen_plane.count()) / samples;
  result.angle_deg = seen_plane.normalAngleDeg(normal);
  result.seals = flat && result.seen_share >= params.min_seen_share && result.angle_deg <= params.max_angle_deg;
  return result;
}

std::optional<Eigen::Isometry3d> MeasuredSurface::findSeal(const Eigen::Isometry3d& T_base_grasp, double radius,
                                                           double tolerance, const SealCheckParams& params) const {
  if (check(T_base_grasp, radius, tolerance, params).seals) return T_base_grasp;
  const int rings = static_cast<int>(std::floor(params.max_shift / params.shift_step + 1e-9));
  for (int ring = 1; ring <= rings; ++ring) {
    const double shift = ring * params.shift_step;
    const int places = 8 * ring;  // about shift_step apart around the ring
    for (int k = 0; k < places; ++k) {
      const double angle = 2.0 * M_PI * k / places;
      // Along the grasp's own xy plane: the face under the cup, whatever the grasp's tilt.
      const Eigen::Isometry3d slid =
          T_base_grasp * Eigen::Translation3d(shift * std::cos(angle), shift * std::sin(angle), 0.0);
      if (check(slid, radius, tolerance, params).seals) return slid;
    }
  }
  return std::nullopt;
}

}  // namespace binpick::picking
