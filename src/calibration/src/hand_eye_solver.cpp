// solveHandEye: checks the views, solves with OpenCV, rules out inverted poses, judges the fit.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "binpick/core/error.hpp"
#include "cv_eigen.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration {
namespace {

using detail::HandEyeProblem;
using detail::MountTransforms;

// Robot controllers and PnP give rotations orthonormal to ~1e-12; a looser matrix was not
// meant as a rotation (a typo in a file, a scaled pose).
constexpr double kRotationTolerance = 1e-6;

bool isRigid(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  return T.matrix().allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kRotationTolerance &&
         R.determinant() > 0.0;
}

void requireViews(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  if (static_cast<int>(views.size()) < params.min_views) {
    throw core::Error("hand-eye needs at least " + std::to_string(params.min_views) + " views, got " +
                      std::to_string(views.size()));
  }
  for (const HandEyeView& view : views) {
    if (!isRigid(view.T_base_flange)) {
      throw core::Error("hand-eye: view " + view.name + ": the robot pose is not a finite rigid motion");
    }
    if (!isRigid(view.T_camera_board)) {
      throw core::Error("hand-eye: view " + view.name + ": the board pose is not a finite rigid motion");
    }
  }
}

std::string describe(const PoseDifference& rms) {
  std::ostringstream text;
  text.precision(3);
  text << rms.translation_mm << " mm, " << rms.rotation_deg << " deg RMS";
  return text.str();
}

// Inverted poses (flange->base) and the wrong setup are the same mistake (hand_eye_internal.hpp):
// when the poses fit much better inverted, that is what happened.
void rejectInvertedPoses(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                         const PoseDifference& as_given) {
  PoseDifference inverted;
  try {
    const HandEyeProblem problem = detail::makeProblem(views, params.setup, true);
    inverted = detail::rmsOf(detail::residualsOf(problem, detail::solveMounts(problem, params).mounts));
  } catch (const core::Error&) {
    return;  // no solution inverted: nothing fits better
  }
  const double ratio = params.inverted_fit_ratio;
  if (!(as_given.translation_mm > ratio * inverted.translation_mm &&
        as_given.rotation_deg > ratio * inverted.rotation_deg)) {
    return;
  }
  const HandEyeSetup other =
      params.setup == HandEyeSetup::EyeToHand ? HandEyeSetup::EyeInHand : HandEyeSetup::EyeToHand;
  throw core::Error("hand-eye: the robot poses look inverted (flange->base): they fit with " + describe(inverted) +
                    " inverted but " + describe(as_given) +
                    " as given. Give T_base_flange, the flange in the base frame as the teach pendant "
                    "shows it, or check the setup: the poses also fit " +
                    handEyeSetupName(other));
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

void markOutliers(HandEyeResult& result, const HandEyeParams& params) {
  std::vector<double> mm, deg;
  for (const HandEyeResidual& r : result.residuals) {
    mm.push_back(r.translation_mm);
    deg.push_back(r.rotation_deg);
  }
  const double mm_limit = std::max(params.outlier_factor * median(mm), params.outlier_floor_mm);
  const double deg_limit = std::max(params.outlier_factor * median(deg), params.outlier_floor_deg);
  for (HandEyeResidual& r : result.residuals) {
    r.outlier = r.translation_mm > mm_limit || r.rotation_deg > deg_limit;
    if (!r.outlier) continue;
    std::ostringstream text;
    text.precision(3);
    text << "view " << r.name << ": residual " << r.translation_mm << " mm, " << r.rotation_deg
         << " deg is an outlier (limits " << mm_limit << " mm, " << deg_limit
         << " deg): check its robot pose and its image";
    result.warnings.push_back(text.str());
  }
}

void judgeFit(HandEyeResult& result, const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  if (result.rms_mm <= params.max_rms_mm && result.rms_deg <= params.max_rms_deg) return;
  std::ostringstream text;
  text.precision(3);
  text << "the residuals (" << describe({result.rms_mm, result.rms_deg}) << ") exceed " << params.max_rms_mm
       << " mm or " << params.max_rms_deg
       << " deg: wrong robot poses, board size or camera intrinsics, or something moved";
  for (const HandEyeResidual& r : result.residuals) {
    if (r.outlier) text << "; outlier " << r.name;
  }
  const std::string blamed = detail::blameViews(views, params);
  if (!blamed.empty()) text << "; " << blamed;
  result.failure = text.str();
}

// One solve of `views` without the views in `dropped`: the residuals of every view (the
// dropped ones marked and out of the RMS).
HandEyeResult solveKeeping(const std::vector<HandEyeView>& views, const std::vector<std::size_t>& dropped,
                           const HandEyeParams& params) {
  std::vector<HandEyeView> kept;
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (std::find(dropped.begin(), dropped.end(), i) == dropped.end()) kept.push_back(views[i]);
  }
  const HandEyeProblem problem = detail::makeProblem(kept, params.setup, false);
  detail::requireRotationSpread(problem, params);
  const detail::Solution solution = detail::solveMounts(problem, params);
  HandEyeResult result;
  result.setup = params.setup;
  result.method = params.method;
  result.start = solution.start;
  result.refined = solution.refined;
  result.T_mount_camera = solution.mounts.camera;
  result.T_mount_board = solution.mounts.board;
  result.residuals = detail::residualsOf(detail::makeProblem(views, params.setup, false), solution.mounts);
  for (const std::size_t i : dropped) {
    result.residuals[i].dropped = true;
    result.dropped.push_back(views[i].name);
  }
  const PoseDifference rms = detail::rmsOf(result.residuals);
  result.rms_mm = rms.translation_mm;
  result.rms_deg = rms.rotation_deg;
  return result;
}

std::string disagreement(const HandEyeResidual& left_out, const HandEyeResult& without) {
  std::ostringstream text;
  text.precision(3);
  text << "view " << left_out.name << " disagrees with the others: " << left_out.translation_mm << " mm, "
       << left_out.rotation_deg << " deg from where their solution puts it; without it they fit to "
       << describe({without.rms_mm, without.rms_deg});
  return text.str();
}

// Views that disagree with the others: dropped (params.drop_outliers) or warned about by name.
HandEyeResult handleDisagreeingViews(const std::vector<HandEyeView>& views, const HandEyeParams& params,
                                     HandEyeResult result) {
  const std::vector<HandEyeResidual> left_out = detail::leaveOneOutResiduals(views, params);
  const std::vector<std::size_t> suspects = detail::disagreeingViews(left_out, params);
  if (suspects.empty()) return result;
  const bool can_drop = static_cast<int>(views.size() - suspects.size()) >= params.min_views;
  HandEyeResult without = result;
  try {
    without = solveKeeping(views, suspects, params);
  } catch (const core::Error&) {
    return result;  // the others alone are not enough to tell
  }
  std::vector<std::string> notes;
  for (const std::size_t i : suspects) {
    std::string note = disagreement(left_out[i], without);
    if (params.drop_outliers && can_drop) {
      note += ": dropped";
    } else if (params.drop_outliers) {
      note += ": kept, dropping it would leave fewer than " + std::to_string(params.min_views) + " views";
    } else {
      note += ": check its robot pose and image, or leave it out (--drop-outliers)";
    }
    notes.push_back(note);
  }
  HandEyeResult& chosen = params.drop_outliers && can_drop ? without : result;
  // The residual-based outlier warnings of these views say less than the notes.
  for (const std::size_t i : suspects) {
    const std::string prefix = "view " + views[i].name + ": residual";
    chosen.warnings.erase(std::remove_if(chosen.warnings.begin(), chosen.warnings.end(),
                                         [&](const std::string& w) { return w.rfind(prefix, 0) == 0; }),
                          chosen.warnings.end());
  }
  for (const std::size_t i : suspects) chosen.residuals[i].outlier = true;
  chosen.warnings.insert(chosen.warnings.end(), notes.begin(), notes.end());
  return chosen;
}

}  // namespace

HandEyeResult solveHandEye(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  params.validate();
  requireViews(views, params);
  HandEyeResult result = solveKeeping(views, {}, params);
  const PoseDifference rms{result.rms_mm, result.rms_deg};
  detail::rejectPositionsInMetres(views, params, rms);
  rejectInvertedPoses(views, params, rms);
  markOutliers(result, params);
  result = handleDisagreeingViews(views, params, std::move(result));
  std::vector<HandEyeView> kept;
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (!result.residuals[i].dropped) kept.push_back(views[i]);
  }
  const std::string board = detail::boardSizeWarning(kept, params, {result.rms_mm, result.rms_deg});
  if (!board.empty()) result.warnings.push_back(board);
  judgeFit(result, kept, params);
  return result;
}

}  // namespace binpick::calibration

// Whether the robot's motion determines the rotation. AX = XB-type problems need rotations
// about at least two non-parallel axes (Tsai and Lenz): with one axis, the rotation about the
// rest and the translation along that axis are free; with little rotation at all, noise
// decides the answer.
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
      const Eigen::AngleAxisd motion(problem.robot[i].linear().transpose() * problem.robot[j].linear());
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
    message << "hand-eye: too little rotation between the views: the largest is " << spread.largest_deg << " deg ("
            << spread.largest_pair << "), needs at least " << params.min_rotation_deg
            << " deg; tilt and turn the flange between views, the rotation is otherwise"
               " unobservable";
    throw core::Error(message.str());
  }
  if (spread.second_axis_deg < params.min_axis_spread_deg) {
    message << "hand-eye: the robot rotates about one axis only (spread about a second axis " << spread.second_axis_deg
            << " deg RMS, needs " << params.min_axis_spread_deg
            << "); the rotation about it and the translation along it are unobservable: turn"
               " the flange about at least two different axes between views";
    throw core::Error(message.str());
  }
}

}  // namespace binpick::calibration::detail

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

bool isRobotWorld(HandEyeMethod method) { return method == HandEyeMethod::Shah || method == HandEyeMethod::Li; }

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
      world2cam.rotations, world2cam.translations, base2gripper.rotations, base2gripper.translations, R_x, t_x, R_z,
      t_z, method == HandEyeMethod::Shah ? cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH : cv::CALIB_ROBOT_WORLD_HAND_EYE_LI);
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
  cv::calibrateHandEye(gripper2base.rotations, gripper2base.translations, target2cam.rotations, target2cam.translations,
                       R, t, handEyeFlag(method));
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

// Every OpenCV method, the one whose views fit best in mm (translation at the board carries the
// rotation's error too, times the lever arm).
Solution bestOpenCvStart(const HandEyeProblem& problem) {
  Solution best;
  double best_mm = std::numeric_limits<double>::infinity();
  std::string last_error = "no method";
  for (const HandEyeMethod method : allHandEyeMethods()) {
    try {
      const MountTransforms mounts = solveWithOpenCv(problem, method);
      const double mm = rmsOf(residualsOf(problem, mounts)).translation_mm;
      if (mm < best_mm) {
        best_mm = mm;
        best = {mounts, method, false};
      }
    } catch (const core::Error& e) {
      last_error = e.what();
    }
  }
  if (!std::isfinite(best_mm)) throw core::Error("hand-eye (auto): no method found a solution; " + last_error);
  return best;
}

}  // namespace

Solution solveMounts(const HandEyeProblem& problem, const HandEyeParams& params) {
  Solution solution;
  if (params.method == HandEyeMethod::Auto) {
    solution = bestOpenCvStart(problem);
  } else {
    solution = {solveWithOpenCv(problem, params.method), params.method, false};
  }
  if (params.refine || params.method == HandEyeMethod::Auto) {
    solution.mounts = refineMounts(problem, solution.mounts);
    solution.refined = true;
  }
  return solution;
}

MountTransforms solveQuickly(const HandEyeProblem& problem, const HandEyeParams& params) {
  return solveWithOpenCv(problem, params.method == HandEyeMethod::Auto ? HandEyeMethod::Shah : params.method);
}

MountTransforms solveWithOpenCv(const HandEyeProblem& problem, HandEyeMethod method) {
  MountTransforms mounts;
  try {
    mounts = isRobotWorld(method) ? robotWorld(problem, method) : handEye(problem, method);
  } catch (const cv::Exception& e) {
    throw core::Error("hand-eye (" + handEyeMethodName(method) + "): OpenCV failed: " + e.what());
  }
  if (!finite(mounts.camera) || !finite(mounts.board)) {
    throw core::Error("hand-eye (" + handEyeMethodName(method) +
                      "): OpenCV's solution is not finite; the views do not determine the transforms");
  }
  return mounts;
}

}  // namespace binpick::calibration::detail
