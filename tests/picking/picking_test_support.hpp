#pragma once
// Poses and a plain scene for the pick-planning tests: the bin at the base origin (default
// BinBox: 400 x 300 mm, walls 150 mm high) and one grasp reaching straight down onto a part's
// top, 20 mm above its origin.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "binpick/picking/picking.hpp"

namespace binpick::picking::test {

inline double radians(double deg) { return deg * M_PI / 180.0; }
inline double degrees(double rad) { return rad * 180.0 / M_PI; }

inline Eigen::Matrix3d rotX(double deg) {
  return Eigen::AngleAxisd(radians(deg), Eigen::Vector3d::UnitX()).toRotationMatrix();
}
inline Eigen::Matrix3d rotY(double deg) {
  return Eigen::AngleAxisd(radians(deg), Eigen::Vector3d::UnitY()).toRotationMatrix();
}
inline Eigen::Matrix3d rotZ(double deg) {
  return Eigen::AngleAxisd(radians(deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

inline Eigen::Isometry3d pose(const Eigen::Vector3d& translation,
                              const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = translation;
  T.linear() = rotation;
  return T;
}

// Tool z (the approach) along model -z, tool x along model x.
inline Grasp topGrasp(const std::string& name = "top") { return {name, pose({0, 0, 0.02}, rotX(180))}; }

inline PickParams topGraspParams() {
  PickParams params;
  params.grasps = {topGrasp()};
  return params;
}

inline DetectedPart part(const Eigen::Vector3d& translation,
                         const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(), double score = 1.0) {
  return {pose(translation, rotation), score};
}

// Rotation angle between two rotations, degrees.
inline double angleBetweenDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return degrees(Eigen::AngleAxisd(a.transpose() * b).angle());
}

inline ::testing::AssertionResult samePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double tolerance_mm,
                                           double tolerance_deg) {
  const double distance_mm = 1000.0 * (a.translation() - b.translation()).norm();
  const double angle_deg = angleBetweenDeg(a.linear(), b.linear());
  if (distance_mm <= tolerance_mm && angle_deg <= tolerance_deg) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "poses differ by " << distance_mm << " mm and " << angle_deg << " deg";
}

// The single pick of a one-part plan, or a failure saying why there is none.
inline ::testing::AssertionResult picksOne(const PickPlan& plan) {
  if (plan.picks.size() == 1) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << plan.picks.size() << " picks; rejected tilt " << plan.rejected.tilt
                                       << ", bin " << plan.rejected.bin << ", cloud " << plan.rejected.cloud
                                       << ", avoided " << plan.rejected.avoided << ", invalid "
                                       << plan.rejected.invalid;
}

}  // namespace binpick::picking::test
