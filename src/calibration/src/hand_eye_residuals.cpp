// The hand-eye problem in one form for both setups, and how well transforms fit it.
#include <cmath>
#include <limits>

#include "hand_eye_internal.hpp"

namespace binpick::calibration {
namespace detail {

HandEyeProblem makeProblem(const std::vector<HandEyeView>& views, HandEyeSetup setup,
                           bool inverted) {
  // Eye-in-hand wants T_base_flange, eye-to-hand its inverse; inverting the given poses flips
  // which one each setup gets.
  const bool invert = (setup == HandEyeSetup::EyeToHand) != inverted;
  HandEyeProblem problem;
  problem.robot_is_flange_base = invert;
  for (const HandEyeView& view : views) {
    problem.names.push_back(view.name);
    problem.robot.push_back(invert ? view.T_base_flange.inverse() : view.T_base_flange);
    problem.camera.push_back(view.T_camera_board);
  }
  return problem;
}

Eigen::Isometry3d predictedBoard(const HandEyeProblem& problem, std::size_t view,
                                 const Eigen::Isometry3d& T_mount_camera) {
  return problem.robot[view] * T_mount_camera * problem.camera[view];
}

std::vector<HandEyeResidual> residualsOf(const HandEyeProblem& problem,
                                         const MountTransforms& mounts) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<HandEyeResidual> residuals;
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    const PoseDifference d = poseDifference(mounts.board, predictedBoard(problem, i, mounts.camera));
    HandEyeResidual r;
    r.name = problem.names[i];
    r.translation_mm = std::isfinite(d.translation_mm) ? d.translation_mm : kInfinity;
    r.rotation_deg = std::isfinite(d.rotation_deg) ? d.rotation_deg : kInfinity;
    residuals.push_back(r);
  }
  return residuals;
}

PoseDifference rmsOf(const std::vector<HandEyeResidual>& residuals) {
  PoseDifference rms;
  if (residuals.empty()) return rms;
  for (const HandEyeResidual& r : residuals) {
    rms.translation_mm += r.translation_mm * r.translation_mm;
    rms.rotation_deg += r.rotation_deg * r.rotation_deg;
  }
  const auto n = static_cast<double>(residuals.size());
  rms.translation_mm = std::sqrt(rms.translation_mm / n);
  rms.rotation_deg = std::sqrt(rms.rotation_deg / n);
  return rms;
}

}  // namespace detail

std::vector<HandEyeResidual> handEyeResiduals(const std::vector<HandEyeView>& views,
                                              HandEyeSetup setup,
                                              const Eigen::Isometry3d& T_mount_camera,
                                              const Eigen::Isometry3d& T_mount_board) {
  const detail::HandEyeProblem problem = detail::makeProblem(views, setup, false);
  return detail::residualsOf(problem, {T_mount_camera, T_mount_board});
}

}  // namespace binpick::calibration
