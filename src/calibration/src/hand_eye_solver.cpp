// solveHandEye: checks the views, solves with OpenCV, rules out inverted poses, judges the fit.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "binpick/io/error.hpp"
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
  return T.matrix().allFinite() &&
         (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kRotationTolerance &&
         R.determinant() > 0.0;
}

void requireViews(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  if (static_cast<int>(views.size()) < params.min_views) {
    throw Error("hand-eye needs at least " + std::to_string(params.min_views) +
                " views, got " + std::to_string(views.size()));
  }
  for (const HandEyeView& view : views) {
    if (!isRigid(view.T_base_flange)) {
      throw Error("hand-eye: view " + view.name + ": the robot pose is not a finite rigid motion");
    }
    if (!isRigid(view.T_camera_board)) {
      throw Error("hand-eye: view " + view.name + ": the board pose is not a finite rigid motion");
    }
  }
}

MountTransforms solve(const HandEyeProblem& problem, const HandEyeParams& params) {
  const MountTransforms start = detail::solveWithOpenCv(problem, params.method);
  return params.refine ? detail::refineMounts(problem, start) : start;
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
    inverted = detail::rmsOf(detail::residualsOf(problem, solve(problem, params)));
  } catch (const Error&) {
    return;  // no solution inverted: nothing fits better
  }
  const double ratio = params.inverted_fit_ratio;
  if (!(as_given.translation_mm > ratio * inverted.translation_mm &&
        as_given.rotation_deg > ratio * inverted.rotation_deg)) {
    return;
  }
  const HandEyeSetup other = params.setup == HandEyeSetup::EyeToHand ? HandEyeSetup::EyeInHand
                                                                     : HandEyeSetup::EyeToHand;
  throw Error("hand-eye: the robot poses look inverted (flange->base): they fit with " +
              describe(inverted) + " inverted but " + describe(as_given) +
              " as given. Give T_base_flange, the flange in the base frame as the teach pendant "
              "shows it, or check the setup: the poses also fit " + handEyeSetupName(other));
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

void judgeFit(HandEyeResult& result, const std::vector<HandEyeView>& views,
              const HandEyeParams& params) {
  if (result.rms_mm <= params.max_rms_mm && result.rms_deg <= params.max_rms_deg) return;
  std::ostringstream text;
  text.precision(3);
  text << "the residuals (" << describe({result.rms_mm, result.rms_deg}) << ") exceed "
       << params.max_rms_mm << " mm or " << params.max_rms_deg
       << " deg: wrong robot poses, board size or camera intrinsics, or something moved";
  for (const HandEyeResidual& r : result.residuals) {
    if (r.outlier) text << "; outlier " << r.name;
  }
  const std::string blamed = detail::blameViews(views, params);
  if (!blamed.empty()) text << "; " << blamed;
  result.failure = text.str();
}

}  // namespace

HandEyeResult solveHandEye(const std::vector<HandEyeView>& views, const HandEyeParams& params) {
  params.validate();
  requireViews(views, params);
  const HandEyeProblem problem = detail::makeProblem(views, params.setup, false);
  detail::requireRotationSpread(problem, params);
  const MountTransforms mounts = solve(problem, params);

  HandEyeResult result;
  result.setup = params.setup;
  result.method = params.method;
  result.T_mount_camera = mounts.camera;
  result.T_mount_board = mounts.board;
  result.residuals = detail::residualsOf(problem, mounts);
  const PoseDifference rms = detail::rmsOf(result.residuals);
  result.rms_mm = rms.translation_mm;
  result.rms_deg = rms.rotation_deg;
  rejectInvertedPoses(views, params, rms);
  markOutliers(result, params);
  judgeFit(result, views, params);
  return result;
}

}  // namespace binpick::calibration
