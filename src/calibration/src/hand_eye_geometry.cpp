// Rigid-transform helpers of the hand-eye solver: angles, means, differences.
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "hand_eye_internal.hpp"

namespace binpick::calibration {
namespace detail {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

}  // namespace

double rotationAngleDeg(const Eigen::Matrix3d& R) {
  // atan2 of the axis part against the trace part: exact near 0 and 180 degrees, where acos of
  // the trace alone loses half the digits.
  const Eigen::Vector3d axis(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (R.trace() - 1.0)) * kDegreesPerRadian;
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& M) {
  if (!M.allFinite()) return M;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

Eigen::Isometry3d meanPose(const std::vector<Eigen::Isometry3d>& poses) {
  Eigen::Matrix3d rotation_sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d translation_sum = Eigen::Vector3d::Zero();
  for (const Eigen::Isometry3d& pose : poses) {
    rotation_sum += pose.linear();
    translation_sum += pose.translation();
  }
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = nearestRotation(rotation_sum);
  mean.translation() = translation_sum / static_cast<double>(std::max<std::size_t>(poses.size(), 1));
  return mean;
}

}  // namespace detail

PoseDifference poseDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  PoseDifference d;
  d.translation_mm = 1000.0 * (a.translation() - b.translation()).norm();
  d.rotation_deg = detail::rotationAngleDeg(a.linear().transpose() * b.linear());
  return d;
}

}  // namespace binpick::calibration
