#pragma once
// Seeded random rotations and poses, and the distances the protocol tests compare with.
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "binpick/core/orientation.hpp"

namespace binpick::test {

constexpr core::Orientation kAllOrientations[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                                  core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                                  core::Orientation::EulerXYZ};

constexpr double kPi = 3.14159265358979323846;
inline double degrees(double radians) { return radians * 180.0 / kPi; }
inline double radians(double degrees) { return degrees * kPi / 180.0; }

// Uniform over SO(3): a normalised 4D Gaussian is a uniform unit quaternion.
inline Eigen::Matrix3d randomRotation(std::mt19937& random) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(random), normal(random), normal(random), normal(random));
  return q.normalized().toRotationMatrix();
}

// A pose with x, y, z uniform in +-reach metres.
inline Eigen::Isometry3d randomPose(std::mt19937& random, double reach) {
  std::uniform_real_distribution<double> position(-reach, reach);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = randomRotation(random);
  pose.translation() = Eigen::Vector3d(position(random), position(random), position(random));
  return pose;
}

// The angle of the rotation taking a to b, degrees.
inline double angleBetweenDegrees(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return degrees(Eigen::AngleAxisd(a.transpose() * b).angle());
}

inline Eigen::Matrix3d rotationX(double degreesAngle) {
  return Eigen::AngleAxisd(radians(degreesAngle), Eigen::Vector3d::UnitX()).toRotationMatrix();
}
inline Eigen::Matrix3d rotationY(double degreesAngle) {
  return Eigen::AngleAxisd(radians(degreesAngle), Eigen::Vector3d::UnitY()).toRotationMatrix();
}
inline Eigen::Matrix3d rotationZ(double degreesAngle) {
  return Eigen::AngleAxisd(radians(degreesAngle), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace binpick::test
