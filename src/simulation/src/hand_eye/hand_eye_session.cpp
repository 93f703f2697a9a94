// simulateHandEyeSession: board poses the camera can see, the robot poses that put the board
// there, and what the robot reports (those poses with noise).
#include <cmath>
#include <cstdio>

#include "binpick/simulation/hand_eye_session.hpp"
#include "random.hpp"

namespace binpick::simulation {
namespace {

// Own random stream under the seed (random.hpp), apart from the board poses (10).
constexpr uint32_t kRobotNoiseStream = 20;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

std::string viewName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "view_%02d", index);
  return name;
}

// Box-Muller from two uniforms of the generator: results fixed by this code, not by the
// standard library's distributions.
Eigen::Vector3d gaussianVector(detail::Rng& rng) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const double u1 = 1.0 - detail::uniform01(rng);  // (0, 1]: log is finite
    const double u2 = detail::uniform01(rng);
    v(i) = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  }
  return v;
}

// The position error in the base frame, the orientation error about the flange's own axes.
Eigen::Isometry3d reported(const Eigen::Isometry3d& truth, const HandEyeSessionParams& params, detail::Rng& rng) {
  const Eigen::Vector3d position_error = gaussianVector(rng) * (params.robot_noise_mm / 1000.0);
  const Eigen::Vector3d rotation_error = gaussianVector(rng) * (params.robot_noise_deg * kDegree);
  Eigen::Isometry3d pose = truth;
  pose.translation() += position_error;
  if (rotation_error.norm() > 0.0) {
    pose.linear() = truth.linear() * Eigen::AngleAxisd(rotation_error.norm(), rotation_error.normalized()).matrix();
  }
  return pose;
}

// The flange pose that puts the board at T_camera_board in the camera's view.
Eigen::Isometry3d flangePose(const HandEyeSessionParams& p, const Eigen::Isometry3d& T_camera_board) {
  if (p.setup == calibration::HandEyeSetup::EyeToHand) {
    return p.T_base_camera * T_camera_board * p.T_flange_board.inverse();
  }
  return p.T_base_board * T_camera_board.inverse() * p.T_flange_camera.inverse();
}

}  // namespace

HandEyeSession simulateHandEyeSession(const HandEyeSessionParams& params) {
  params.validate();
  const bool eye_to_hand = params.setup == calibration::HandEyeSetup::EyeToHand;
  HandEyeSession session;
  session.setup = params.setup;
  session.T_mount_camera = eye_to_hand ? params.T_base_camera : params.T_flange_camera;
  session.T_mount_board = eye_to_hand ? params.T_flange_board : params.T_base_board;

  const CalibrationBoard board(params.board);
  BoardPoseParams pose_params = params.poses;
  pose_params.count = params.views;
  pose_params.seed = params.seed;
  detail::Rng noise = detail::makeRng(params.seed, kRobotNoiseStream);
  const std::vector<Eigen::Isometry3d> boards = randomBoardPoses(board, params.rig, pose_params);
  for (std::size_t i = 0; i < boards.size(); ++i) {
    HandEyeSessionView view;
    view.name = viewName(static_cast<int>(i));
    view.T_camera_board = boards[i];
    view.T_base_flange_true = flangePose(params, boards[i]);
    view.T_base_flange = reported(view.T_base_flange_true, params, noise);
    session.views.push_back(view);
  }
  return session;
}

}  // namespace binpick::simulation
