// poseError: the estimate is compared with every pose that looks identical to the truth, i.e.
// the truth composed with a symmetry of the model (T_true * S), and the closest one counts.
#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/simulation/parts.hpp"

namespace binpick::simulation {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// Rotation angle of R in radians, via the quaternion: accurate near 0 where acos of the trace
// loses half of the digits.
double rotationAngle(const Eigen::Matrix3d& rotation) {
  const Eigen::Quaterniond q(rotation);
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

PoseError poseError(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth, const Symmetry& symmetry) {
  PoseError error;
  // Every symmetry rotation is about the model origin, so the origin itself never moves: the
  // translation error needs no minimisation (this also holds along a continuous axis).
  error.translation = (estimate.translation() - truth.translation()).norm();

  const Eigen::Matrix3d r_est = estimate.linear();
  const Eigen::Matrix3d r_true = truth.linear();
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  double best = std::numeric_limits<double>::infinity();
  // Identity is always a symmetry, even if a caller emptied the list.
  std::vector<Eigen::Matrix3d> rotations = symmetry.discrete;
  rotations.push_back(identity);
  for (const auto& s : rotations) {
    const Eigen::Matrix3d r_equivalent = r_true * s;
    double angle = 0.0;
    if (symmetry.continuous_axis) {
      // The smallest rotation between R_est and any R_equivalent * Rot(axis, theta) is the angle
      // between where the two rotations send the axis.
      const Eigen::Vector3d axis = symmetry.continuous_axis->normalized();
      angle = angleBetween(r_est * axis, r_equivalent * axis);
    } else {
      angle = rotationAngle(r_equivalent.transpose() * r_est);
    }
    best = std::min(best, angle);
  }
  error.rotation_deg = best * kDegreesPerRadian;
  return error;
}

}  // namespace binpick::simulation
