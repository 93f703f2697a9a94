// The hand-eye problem in one form for both setups (hand_eye_internal.hpp), how well transforms fit
// it, rigid-transform helpers (angles, means, differences), and the names of setups, methods and
// transforms as the CLI and the result file show them.
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "binpick/calibration/hand_eye.hpp"
#include "binpick/core/error.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration {
namespace {

const std::array<std::pair<HandEyeMethod, const char*>, 7> kMethods = {{
    {HandEyeMethod::Shah, "shah"},
    {HandEyeMethod::Li, "li"},
    {HandEyeMethod::Tsai, "tsai"},
    {HandEyeMethod::Park, "park"},
    {HandEyeMethod::Horaud, "horaud"},
    {HandEyeMethod::Andreff, "andreff"},
    {HandEyeMethod::Daniilidis, "daniilidis"},
}};

}  // namespace

std::string handEyeSetupName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "eye-to-hand" : "eye-in-hand";
}

HandEyeSetup handEyeSetupFromName(const std::string& name) {
  if (name == "eye-to-hand") return HandEyeSetup::EyeToHand;
  if (name == "eye-in-hand") return HandEyeSetup::EyeInHand;
  throw core::Error("unknown hand-eye setup '" + name +
                    "' (eye-to-hand: fixed camera, board on the flange; eye-in-hand: camera on the "
                    "flange, board fixed)");
}

std::string cameraTransformName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "T_base_camera" : "T_flange_camera";
}

std::string boardTransformName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "T_flange_board" : "T_base_board";
}

std::string handEyeMethodName(HandEyeMethod method) {
  if (method == HandEyeMethod::Auto) return "auto";
  for (const auto& [value, name] : kMethods) {
    if (value == method) return name;
  }
  throw core::Error("handEyeMethodName: unknown method");
}

HandEyeMethod handEyeMethodFromName(const std::string& name) {
  if (name == "auto") return HandEyeMethod::Auto;
  std::string names = "auto";
  for (const auto& [value, known] : kMethods) {
    if (name == known) return value;
    names += ", " + std::string(known);
  }
  throw core::Error("unknown hand-eye method '" + name + "' (" + names + ")");
}

std::vector<HandEyeMethod> allHandEyeMethods() {
  std::vector<HandEyeMethod> methods;
  for (const auto& entry : kMethods) methods.push_back(entry.first);
  return methods;
}

namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "HandEyeParams", field, rule, value);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }
bool nonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void HandEyeParams::validate() const {
  // OpenCV's solvers need 3 views; fewer than 4 leave no residual to judge a view by.
  require(min_views >= 4, "min_views", ">= 4", min_views);
  require(nonNegative(min_rotation_deg) && min_rotation_deg < 180.0, "min_rotation_deg", "in [0, 180)",
          min_rotation_deg);
  require(nonNegative(min_axis_spread_deg) && min_axis_spread_deg < 180.0, "min_axis_spread_deg", "in [0, 180)",
          min_axis_spread_deg);
  require(std::isfinite(inverted_fit_ratio) && inverted_fit_ratio > 1.0, "inverted_fit_ratio", "> 1",
          inverted_fit_ratio);
  require(std::isfinite(outlier_factor) && outlier_factor > 1.0, "outlier_factor", "> 1", outlier_factor);
  require(nonNegative(outlier_floor_mm), "outlier_floor_mm", ">= 0", outlier_floor_mm);
  require(nonNegative(outlier_floor_deg), "outlier_floor_deg", ">= 0", outlier_floor_deg);
  require(positive(outlier_mad_factor), "outlier_mad_factor", "positive", outlier_mad_factor);
  require(positive(warn_rms_mm), "warn_rms_mm", "positive", warn_rms_mm);
  require(positive(max_rms_mm), "max_rms_mm", "positive", max_rms_mm);
  require(positive(max_rms_deg), "max_rms_deg", "positive", max_rms_deg);
}

namespace detail {

HandEyeProblem makeProblem(const std::vector<HandEyeView>& views, HandEyeSetup setup, bool inverted) {
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

std::vector<HandEyeResidual> residualsOf(const HandEyeProblem& problem, const MountTransforms& mounts) {
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
  int n = 0;
  for (const HandEyeResidual& r : residuals) {
    if (r.dropped) continue;
    rms.translation_mm += r.translation_mm * r.translation_mm;
    rms.rotation_deg += r.rotation_deg * r.rotation_deg;
    ++n;
  }
  if (n == 0) return rms;
  rms.translation_mm = std::sqrt(rms.translation_mm / n);
  rms.rotation_deg = std::sqrt(rms.rotation_deg / n);
  return rms;
}

}  // namespace detail

std::vector<HandEyeResidual> handEyeResiduals(const std::vector<HandEyeView>& views, HandEyeSetup setup,
                                              const Eigen::Isometry3d& T_mount_camera,
                                              const Eigen::Isometry3d& T_mount_board) {
  const detail::HandEyeProblem problem = detail::makeProblem(views, setup, false);
  return detail::residualsOf(problem, {T_mount_camera, T_mount_board});
}

namespace detail {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

}  // namespace

double rotationAngleDeg(const Eigen::Matrix3d& R) {
  // atan2 of the axis part against the trace part: exact near 0 and 180 degrees, where acos of
  // the trace alone loses half the digits.
  const Eigen::Vector3d axis(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (R.trace() - 1.0)) * kDegreesPerRadian;
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& M) {
  if (!M.allFinite()) return M;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

Eigen::Isometry3d meanPose(const std::vector<Eigen::Isometry3d>& poses) {
  Eigen::Matrix3d rotation_sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d translation_sum = Eigen::Vector3d::Zero();
  for (const Eigen::Isometry3d& pose : poses) {
    rotation_sum += pose.linear();
    translation_sum += pose.translation();
  }
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = nearestRotation(rotation_sum);
  mean.translation() = translation_sum / static_cast<double>(std::max<std::size_t>(poses.size(), 1));
  return mean;
}

}  // namespace detail

PoseDifference poseDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  PoseDifference d;
  d.translation_mm = 1000.0 * (a.translation() - b.translation()).norm();
  d.rotation_deg = detail::rotationAngleDeg(a.linear().transpose() * b.linear());
  return d;
}

std::string handEyeMethodDescription(const HandEyeResult& result) {
  std::string text = handEyeMethodName(result.start) + (result.refined ? "+refine" : "");
  return result.method == HandEyeMethod::Auto ? "auto (" + text + ")" : text;
}

}  // namespace binpick::calibration
