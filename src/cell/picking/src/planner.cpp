// planPicks: per part, the best reachable symmetric grasp; then the order.
#include <algorithm>
#include <cmath>
#include <optional>

#include "approach_check.hpp"
#include "binpick/cell/picking.hpp"
#include "grasp_candidates.hpp"
#include "pick_order.hpp"
#include "rigid.hpp"

namespace binpick::cell {
namespace {

// Detected poses are float refinements: rigid to ~1e-7, far inside this.
constexpr double kPoseTolerance = 1e-4;
// Tilts this close count as equal, so the grasp index and the wrist angle decide.
constexpr double kTiltTieDeg = 1e-6;

bool isValidPart(const DetectedPart& part) {
  return std::isfinite(part.score) && isRigidPose(part.T_base_model, kPoseTolerance);
}

bool isNearAvoided(const Eigen::Vector3d& centre, const std::vector<Eigen::Vector3d>& avoid,
                   double radius) {
  for (const Eigen::Vector3d& failed : avoid) {
    // A non-finite entry gives a NaN distance, which compares false: it avoids nothing.
    if ((centre - failed).squaredNorm() <= radius * radius) return true;
  }
  return false;
}

// How close the tool x axis lies to base +x seen along the approach (cosine, higher is better).
// When the approach runs along base x, base +y stands in, so every pose has a canonical angle.
double wristAlignment(const Eigen::Isometry3d& T_base_grasp) {
  const Eigen::Vector3d approach = T_base_grasp.linear().col(2);
  const auto projected = [&approach](const Eigen::Vector3d& axis) -> Eigen::Vector3d {
    return axis - axis.dot(approach) * approach;
  };
  Eigen::Vector3d reference = projected(Eigen::Vector3d::UnitX());
  if (reference.norm() < 1e-6) reference = projected(Eigen::Vector3d::UnitY());
  return T_base_grasp.linear().col(0).dot(reference.normalized());
}

// Whether `challenger` (no more tilted than the least tilt + kTiltTieDeg) beats `incumbent`:
// the lower grasp index, then the better wrist alignment; a full tie keeps the earlier one.
bool breaksTieBetter(const Pick& challenger, const Pick& incumbent) {
  if (challenger.grasp != incumbent.grasp) return challenger.grasp < incumbent.grasp;
  return wristAlignment(challenger.T_base_grasp) > wristAlignment(incumbent.T_base_grasp);
}

std::vector<Pick> reachablePicks(const DetectedPart& part, int object,
                                 const std::vector<GraspCandidate>& candidates,
                                 const PickParams& params) {
  std::vector<Pick> reachable;
  for (const GraspCandidate& candidate : candidates) {
    const Eigen::Isometry3d T_base_grasp = part.T_base_model * candidate.T_model_grasp;
    const double tilt_deg = approachTiltDeg(T_base_grasp);
    if (tilt_deg > params.max_tilt_deg) continue;
    if (approachHitsBin(T_base_grasp, params)) continue;
    reachable.push_back({object, candidate.grasp, T_base_grasp, tilt_deg});
  }
  return reachable;
}

// The least tilted of the reachable picks, ties broken by breaksTieBetter.
std::optional<Pick> bestPick(const std::vector<Pick>& reachable) {
  if (reachable.empty()) return std::nullopt;
  double least_tilt = reachable.front().tilt_deg;
  for (const Pick& pick : reachable) least_tilt = std::min(least_tilt, pick.tilt_deg);
  std::optional<Pick> best;
  for (const Pick& pick : reachable) {
    if (pick.tilt_deg > least_tilt + kTiltTieDeg) continue;
    if (!best || breaksTieBetter(pick, *best)) best = pick;
  }
  return best;
}

}  // namespace

PickPlan planPicks(const std::vector<DetectedPart>& parts, const std::vector<Eigen::Vector3d>& avoid,
                   const PickParams& params, const MeasuredScene* /*scene*/) {
  params.validate();
  const std::vector<GraspCandidate> candidates = symmetricGraspCandidates(params);
  PickPlan plan;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const DetectedPart& part = parts[i];
    if (!isValidPart(part)) {
      ++plan.rejected.invalid;
      continue;
    }
    if (isNearAvoided(part.T_base_model.translation(), avoid, params.avoid_radius)) {
      ++plan.rejected.avoided;
      continue;
    }
    const auto object = static_cast<int>(i);
    if (auto pick = bestPick(reachablePicks(part, object, candidates, params))) {
      plan.picks.push_back(*pick);
    } else {
      ++plan.rejected.bin;
    }
  }
  sortPicks(plan.picks, parts, params.order);
  return plan;
}

}  // namespace binpick::cell
