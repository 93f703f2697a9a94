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
#include <sstream>

#include "binpick/core/error.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

// A robot's orientation error against its position error: 0.05 degrees against 0.1 mm.
constexpr double kRotationLever = 0.115;  // metres per radian
constexpr int kMaxIterations = 20;
constexpr double kStep = 1e-7;        // numerical derivative step, radians or metres
constexpr double kConverged = 1e-14;  // squared parameter update that ends the iterations

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
      J.col(k) = (residualVector(problem, apply(current, step)) - residualVector(problem, apply(current, -step))) /
                 (2.0 * kStep);
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

// Which views spoil a fit. One wrong image or pose can spoil the fit of every view (two views
// with swapped images give hundreds of millimetres everywhere), so the residuals alone may not
// show the culprits. When the fit is too poor to use, the fewest views whose removal lets the
// rest fit are searched for: every single view first, then every pair, and so on, within a
// budget of solves (each takes about a millisecond).
namespace binpick::calibration::detail {
namespace {

// OpenCV's solvers need 3 views; one more leaves a residual to judge the rest by.
constexpr std::size_t kFewestViews = 4;
constexpr int kMaxSolves = 2000;

struct Fit {
  double rms_mm = 0.0;
  double rms_deg = 0.0;
  bool within(const HandEyeParams& p) const { return rms_mm <= p.max_rms_mm && rms_deg <= p.max_rms_deg; }
};

bool fitWithout(const std::vector<HandEyeView>& views, const std::vector<std::size_t>& dropped,
                const HandEyeParams& params, Fit& fit) {
  std::vector<HandEyeView> rest;
  for (std::size_t i = 0, d = 0; i < views.size(); ++i) {
    if (d < dropped.size() && dropped[d] == i)
      ++d;
    else
      rest.push_back(views[i]);
  }
  try {
    const HandEyeProblem problem = makeProblem(rest, params.setup, false);
    const PoseDifference rms = rmsOf(residualsOf(problem, solveQuickly(problem, params)));
    fit = {rms.translation_mm, rms.rotation_deg};
    return true;
  } catch (const core::Error&) {
    return false;  // OpenCV found no solution for these views
  }
}

// The next combination of `chosen.size()` indices out of n in lexicographic order; false after
// the last.
bool nextCombination(std::vector<std::size_t>& chosen, std::size_t n) {
  for (std::size_t i = chosen.size(); i-- > 0;) {
    if (chosen[i] < n - chosen.size() + i) {
      ++chosen[i];
      for (std::size_t j = i + 1; j < chosen.size(); ++j) chosen[j] = chosen[j - 1] + 1;
      return true;
    }
  }
  return false;
}

std::string sentence(const std::vector<HandEyeView>& views, const std::vector<std::size_t>& dropped, const Fit& fit) {
  std::ostringstream text;
  text.precision(3);
  text << "the other views fit (" << fit.rms_mm << " mm, " << fit.rms_deg << " deg RMS) without";
  for (const std::size_t i : dropped) text << " " << views[i].name;
  text << ": check their images and robot poses";
  return text.str();
}

}  // namespace

std::string blameViews(std::vector<HandEyeView> views, const HandEyeParams& params) {
  int solves = 0;
  for (std::size_t count = 1; count + kFewestViews <= views.size(); ++count) {
    std::vector<std::size_t> dropped(count);
    for (std::size_t i = 0; i < count; ++i) dropped[i] = i;
    bool found = false;
    std::vector<std::size_t> best;
    Fit best_fit;
    do {
      if (++solves > kMaxSolves) return "";
      Fit fit;
      if (fitWithout(views, dropped, params, fit) && fit.within(params) && (!found || fit.rms_mm < best_fit.rms_mm)) {
        found = true;
        best = dropped;
        best_fit = fit;
      }
    } while (nextCombination(dropped, views.size()));
    if (found) return sentence(views, best, best_fit);
  }
  return "";
}

}  // namespace binpick::calibration::detail
