#pragma once
// Internal to the hand-eye solver. Both setups are one problem: per view i
//   G_i * T_mount_camera * T_camera_board_i = T_mount_board
// with G_i the robot's transform from the camera's mount to the board's mount:
//   eye-to-hand: G_i = T_flange_base_i  (board on the flange, camera on the base)
//   eye-in-hand: G_i = T_base_flange_i  (board on the base, camera on the flange)
// so swapping the setup is the same as inverting every robot pose.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/calibration/hand_eye.hpp"

namespace binpick::calibration::detail {

struct HandEyeProblem {
  std::vector<std::string> names;
  std::vector<Eigen::Isometry3d> robot;   // G_i
  std::vector<Eigen::Isometry3d> camera;  // T_camera_board_i
  bool robot_is_flange_base = false;      // G_i = T_flange_base_i (else T_base_flange_i)
};

// `inverted`: the poses as if they had been given flange->base.
HandEyeProblem makeProblem(const std::vector<HandEyeView>& views, HandEyeSetup setup, bool inverted);

struct MountTransforms {
  Eigen::Isometry3d camera = Eigen::Isometry3d::Identity();  // T_mount_camera
  Eigen::Isometry3d board = Eigen::Isometry3d::Identity();   // T_mount_board
};

// OpenCV's solution; throws core::Error when it is not finite.
MountTransforms solveWithOpenCv(const HandEyeProblem& problem, HandEyeMethod method);
// Gauss-Newton on both transforms from `start`, minimising the pose residuals.
MountTransforms refineMounts(const HandEyeProblem& problem, const MountTransforms& start);

struct Solution {
  MountTransforms mounts;
  HandEyeMethod start = HandEyeMethod::Shah;
  bool refined = false;
};
// params.method, refined when params.refine; Auto: every OpenCV method, the one with the lowest
// residual RMS (mm), refined. Throws core::Error when no method gives a finite solution.
Solution solveMounts(const HandEyeProblem& problem, const HandEyeParams& params);
// For the many solves of a diagnosis: params.method unrefined, Shah for Auto.
MountTransforms solveQuickly(const HandEyeProblem& problem, const HandEyeParams& params);

// The board in its mount as the robot's way predicts it, per view.
Eigen::Isometry3d predictedBoard(const HandEyeProblem& problem, std::size_t view,
                                 const Eigen::Isometry3d& T_mount_camera);
// Per view and RMS; NaN transforms give infinite residuals.
std::vector<HandEyeResidual> residualsOf(const HandEyeProblem& problem, const MountTransforms& mounts);
PoseDifference rmsOf(const std::vector<HandEyeResidual>& residuals);

// The mean of rigid transforms: mean translation, and the rotation nearest the mean matrix.
Eigen::Isometry3d meanPose(const std::vector<Eigen::Isometry3d>& poses);
double rotationAngleDeg(const Eigen::Matrix3d& R);
// The rotation nearest M (Frobenius norm); NaN in, NaN out.
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& M);

// For a fit too poor to use: the views without which the rest fit, as a sentence for the
// failure message ("the other views fit (...) without view_01 view_02: ..."); "" when dropping
// views down to OpenCV's minimum does not help.
std::string blameViews(std::vector<HandEyeView> views, const HandEyeParams& params);

// Throws core::Error when the robot motion leaves the rotation unobservable.
void requireRotationSpread(const HandEyeProblem& problem, const HandEyeParams& params);

// Throws core::Error ("units? ...") when a fit too poor in translation, whose rotation fits,
// fits with the robot positions multiplied by 1000: they were written in metres.
void rejectPositionsInMetres(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                             const PoseDifference& as_given);

// Each view's residual against the solution of the other views (leave one out).
std::vector<HandEyeResidual> leaveOneOutResiduals(const std::vector<HandEyeView>& views, const HandEyeParams& params);
// The indices of the views whose leave-one-out residual stands far above the others'
// (HandEyeParams::outlier_mad_factor and the outlier limits).
std::vector<std::size_t> disagreeingViews(const std::vector<HandEyeResidual>& left_out, const HandEyeParams& params);

// A warning ("" when none) when the residual RMS exceeds params.warn_rms_mm or scaling the
// board's distances fits much better: a wrong board size.
std::string boardSizeWarning(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                             const PoseDifference& as_given);

}  // namespace binpick::calibration::detail
