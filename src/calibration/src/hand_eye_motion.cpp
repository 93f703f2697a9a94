// Whether the robot's motion determines the rotation. AX = XB-type problems need rotations
// about at least two non-parallel axes (Tsai and Lenz): with one axis, the rotation about the
// rest and the translation along that axis are free; with little rotation at all, noise
// decides the answer.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "binpick/io/error.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

struct RotationSpread {
  double largest_deg = 0.0;      // the largest rotation between two views
  double second_axis_deg = 0.0;  // RMS rotation about the second principal axis
  std::string largest_pair;      // the two views of the largest rotation
};

// Rotation vectors of every pairwise motion G_i^-1 G_j, in the frame where the problem's
// rotation axes live; their scatter matrix's second eigenvalue measures how much of the motion
// is about an axis other than the dominant one. The sign of a rotation vector does not matter
// to the scatter matrix, so the order within a pair does not either.
RotationSpread rotationSpread(const HandEyeProblem& problem) {
  RotationSpread spread;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  int pairs = 0;
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    for (std::size_t j = i + 1; j < problem.robot.size(); ++j) {
      const Eigen::AngleAxisd motion(problem.robot[i].linear().transpose() *
                                     problem.robot[j].linear());
      const Eigen::Vector3d w = motion.angle() * motion.axis() * kDegreesPerRadian;
      scatter += w * w.transpose();
      ++pairs;
      if (w.norm() > spread.largest_deg) {
        spread.largest_deg = w.norm();
        spread.largest_pair = problem.names[i] + " and " + problem.names[j];
      }
    }
  }
  if (pairs == 0) return spread;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter / pairs);
  spread.second_axis_deg = std::sqrt(std::max(0.0, eigen.eigenvalues()(1)));  // ascending order
  return spread;
}

}  // namespace

void requireRotationSpread(const HandEyeProblem& problem, const HandEyeParams& params) {
  const RotationSpread spread = rotationSpread(problem);
  std::ostringstream message;
  message.precision(3);
  if (spread.largest_deg < params.min_rotation_deg) {
    message << "hand-eye: too little rotation between the views: the largest is "
            << spread.largest_deg << " deg (" << spread.largest_pair << "), needs at least "
            << params.min_rotation_deg
            << " deg; tilt and turn the flange between views, the rotation is otherwise"
               " unobservable";
    throw Error(message.str());
  }
  if (spread.second_axis_deg < params.min_axis_spread_deg) {
    message << "hand-eye: the robot rotates about one axis only (spread about a second axis "
            << spread.second_axis_deg << " deg RMS, needs " << params.min_axis_spread_deg
            << "); the rotation about it and the translation along it are unobservable: turn"
               " the flange about at least two different axes between views";
    throw Error(message.str());
  }
}

}  // namespace binpick::calibration::detail
