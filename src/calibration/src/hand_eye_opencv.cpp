// The hand-eye problem handed to OpenCV in its own conventions.
//
// cv::calibrateRobotWorldHandEye solves A_i X = Z B_i with A_i = world2cam (T_cam_world),
// B_i = base2gripper (T_gripper_base), X = base2world, Z = gripper2cam. With the board as
// "world" and G_i^-1 as "base2gripper" (hand_eye_internal.hpp), G_i T_mount_camera C_i =
// T_mount_board reads C_i T_mount_board^-1 = T_mount_camera^-1 G_i^-1: X = T_mount_board^-1 and
// Z = T_mount_camera^-1, in both setups.
//
// cv::calibrateHandEye solves for cam2gripper from gripper2base and target2cam. OpenCV's
// eye-in-hand input is gripper2base = T_base_flange = G_i; its documented eye-to-hand input is
// base2gripper = T_flange_base = G_i again, giving cam2base. So gripper2base := G_i and the
// output is T_mount_camera in both setups; the board's mount transform is then the mean of its
// per-view predictions.
#include <opencv2/calib3d.hpp>

#include "binpick/io/error.hpp"
#include "cv_eigen.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

struct CvPoses {
  std::vector<cv::Mat> rotations;
  std::vector<cv::Mat> translations;
  void add(const Eigen::Isometry3d& T) {
    cv::Mat R(3, 3, CV_64F);
    cv::Mat t(3, 1, CV_64F);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T.linear()(r, c);
      t.at<double>(r) = T.translation()(r);
    }
    rotations.push_back(R);
    translations.push_back(t);
  }
};

// OpenCV's rotations are orthonormal only to its solver's precision; Isometry3d::inverse
// assumes they are exactly.
Eigen::Isometry3d fromCv(const cv::Mat& R, const cv::Mat& t) {
  Eigen::Isometry3d T = detail::isometryFromCv(R, t);
  T.linear() = nearestRotation(T.linear());
  return T;
}

bool isRobotWorld(HandEyeMethod method) {
  return method == HandEyeMethod::Shah || method == HandEyeMethod::Li;
}

cv::HandEyeCalibrationMethod handEyeFlag(HandEyeMethod method) {
  switch (method) {
    case HandEyeMethod::Tsai: return cv::CALIB_HAND_EYE_TSAI;
    case HandEyeMethod::Park: return cv::CALIB_HAND_EYE_PARK;
    case HandEyeMethod::Horaud: return cv::CALIB_HAND_EYE_HORAUD;
    case HandEyeMethod::Andreff: return cv::CALIB_HAND_EYE_ANDREFF;
    default: return cv::CALIB_HAND_EYE_DANIILIDIS;
  }
}

MountTransforms robotWorld(const HandEyeProblem& problem, HandEyeMethod method) {
  CvPoses world2cam;
  CvPoses base2gripper;
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    world2cam.add(problem.camera[i]);
    base2gripper.add(problem.robot[i].inverse());
  }
  cv::Mat R_x, t_x, R_z, t_z;
  cv::calibrateRobotWorldHandEye(
      world2cam.rotations, world2cam.translations, base2gripper.rotations,
      base2gripper.translations, R_x, t_x, R_z, t_z,
      method == HandEyeMethod::Shah ? cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH
                                    : cv::CALIB_ROBOT_WORLD_HAND_EYE_LI);
  return {fromCv(R_z, t_z).inverse(), fromCv(R_x, t_x).inverse()};
}

MountTransforms handEye(const HandEyeProblem& problem, HandEyeMethod method) {
  CvPoses gripper2base;
  CvPoses target2cam;
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    gripper2base.add(problem.robot[i]);
    target2cam.add(problem.camera[i]);
  }
  cv::Mat R, t;
  cv::calibrateHandEye(gripper2base.rotations, gripper2base.translations, target2cam.rotations,
                       target2cam.translations, R, t, handEyeFlag(method));
  MountTransforms mounts;
  mounts.camera = fromCv(R, t);
  std::vector<Eigen::Isometry3d> boards;
  for (std::size_t i = 0; i < problem.robot.size(); ++i) {
    boards.push_back(predictedBoard(problem, i, mounts.camera));
  }
  mounts.board = meanPose(boards);
  return mounts;
}

bool finite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

}  // namespace

MountTransforms solveWithOpenCv(const HandEyeProblem& problem, HandEyeMethod method) {
  MountTransforms mounts;
  try {
    mounts = isRobotWorld(method) ? robotWorld(problem, method) : handEye(problem, method);
  } catch (const cv::Exception& e) {
    throw Error("hand-eye (" + handEyeMethodName(method) + "): OpenCV failed: " + e.what());
  }
  if (!finite(mounts.camera) || !finite(mounts.board)) {
    throw Error("hand-eye (" + handEyeMethodName(method) +
                "): OpenCV's solution is not finite; the views do not determine the transforms");
  }
  return mounts;
}

}  // namespace binpick::calibration::detail
