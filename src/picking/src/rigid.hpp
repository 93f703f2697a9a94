#pragma once
// Checks of what the picking settings and the planner are handed: a pose that only looks rigid
// (NaN, a scale, a mirror) would hand the robot nonsense, a NaN length would pass `> 0`. And the
// angle between two directions, as the planner measures tilts and leans.
#include <Eigen/Geometry>
#include <cmath>

namespace binpick::picking {

inline bool isPositive(double value) { return std::isfinite(value) && value > 0.0; }
inline bool isNonNegative(double value) { return std::isfinite(value) && value >= 0.0; }

// Orthonormal within `tolerance` (Frobenius norm of R^T R - I) and not a mirror.
inline bool isRotation(const Eigen::Matrix3d& R, double tolerance) {
  if (!R.allFinite()) return false;
  const double orthonormality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  return orthonormality <= tolerance && R.determinant() > 0.0;
}

// Degrees between two vectors, in [0, 180]: atan2 of sine and cosine stays accurate near 0 and
// 180 degrees, where acos is not.
inline double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// Finite, with a rotation part and an affine bottom row.
inline bool isRigidPose(const Eigen::Isometry3d& T, double tolerance) {
  if (!T.matrix().allFinite()) return false;
  const Eigen::RowVector4d bottom_row_error = T.matrix().row(3) - Eigen::RowVector4d(0, 0, 0, 1);
  const bool affine = bottom_row_error.cwiseAbs().maxCoeff() <= tolerance;
  return affine && isRotation(T.linear(), tolerance);
}

}  // namespace binpick::picking
