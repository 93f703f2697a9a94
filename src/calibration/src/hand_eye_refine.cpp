// Gauss-Newton refinement of both mount transforms after OpenCV's solution.
//
// The cost compares each reported flange pose with the one the camera's way predicts
// (G_i' = T_mount_board T_camera_board_i^-1 T_mount_camera^-1): translation between the flange
// origins, rotation weighed by kRotationLever. At the flange origin the robot's orientation error
// moves nothing, so translation and rotation residuals carry the robot's two errors apart; at the
// board (the reported residual) the orientation error is multiplied by the flange-to-board
// distance, which is 0.9 m eye-in-hand. Measured in docs/hand-eye.md.
#include <Eigen/Cholesky>
#include <cmath>

#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

// A robot's orientation error against its position error: 0.05 degrees against 0.1 mm.
constexpr double kRotationLever = 0.115;  // metres per radian
constexpr int kMaxIterations = 20;
constexpr double kStep = 1e-7;          // numerical derivative step, radians or metres
constexpr double kConverged = 1e-14;    // squared parameter update that ends the iterations

using Vector12 = Eigen::Matrix<double, 12, 1>;

// x = (rotation vector, translation) of a right-multiplied perturbation.
Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, const Eigen::Matrix<double, 6, 1>& x) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = x.head<3>();
  if (w.norm() > 0.0) delta.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).matrix();
  delta.translation() = x.tail<3>();
  return T * delta;
}

MountTransforms apply(const MountTransforms& m, const Vector12& x) {
  return {perturbed(m.camera, x.head<6>()), perturbed(m.board, x.tail<6>())};
}

// The flange pose in the base frame from G (T_base_flange or its inverse).
Eigen::Isometry3d baseFlange(const HandEyeProblem& problem, const Eigen::Isometry3d& G) {
  return problem.robot_is_flange_base ? G.inverse() : G;
}

Eigen::VectorXd residualVector(const HandEyeProblem& problem, const MountTransforms& m) {
  Eigen::VectorXd r(6 * problem.robot.size());
  const Eigen::Isometry3d camera_inverse = m.camera.inverse();
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    const Eigen::Isometry3d predicted = m.board * problem.camera[i].inverse() * camera_inverse;
    const Eigen::Isometry3d reported = baseFlange(problem, problem.robot[i]);
    const Eigen::Isometry3d flange = baseFlange(problem, predicted);
    const Eigen::AngleAxisd rotation(reported.linear().transpose() * flange.linear());
    r.segment<3>(6 * i) = flange.translation() - reported.translation();
    r.segment<3>(6 * i + 3) = kRotationLever * rotation.angle() * rotation.axis();
  }
  return r;
}

}  // namespace

MountTransforms refineMounts(const HandEyeProblem& problem, const MountTransforms& start) {
  MountTransforms current = start;
  Eigen::VectorXd r = residualVector(problem, current);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::MatrixXd J(r.size(), 12);
    for (int k = 0; k < 12; ++k) {
      Vector12 step = Vector12::Zero();
      step(k) = kStep;
      J.col(k) = (residualVector(problem, apply(current, step)) -
                  residualVector(problem, apply(current, -step))) / (2.0 * kStep);
    }
    const Vector12 update = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
    if (!update.allFinite()) break;
    const MountTransforms next = apply(current, update);
    const Eigen::VectorXd next_r = residualVector(problem, next);
    if (!(next_r.squaredNorm() < r.squaredNorm())) break;  // no progress: at the minimum
    current = next;
    r = next_r;
    if (update.squaredNorm() < kConverged) break;
  }
  return current;
}

}  // namespace binpick::calibration::detail
