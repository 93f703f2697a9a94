#pragma once
// Checks of what the picking settings and the planner are handed: a pose that only looks rigid
// (NaN, a scale, a mirror) would hand the robot nonsense, a NaN length would pass `> 0`.
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

// Finite, with a rotation part and an affine bottom row.
inline bool isRigidPose(const Eigen::Isometry3d& T, double tolerance) {
  if (!T.matrix().allFinite()) return false;
  const Eigen::RowVector4d bottom_row_error = T.matrix().row(3) - Eigen::RowVector4d(0, 0, 0, 1);
  const bool affine = bottom_row_error.cwiseAbs().maxCoeff() <= tolerance;
  return affine && isRotation(T.linear(), tolerance);
}

}  // namespace binpick::picking
