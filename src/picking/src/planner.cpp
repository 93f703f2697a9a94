// planPicks: per part, the best-ranked symmetric grasp that passes the tilt, bin, cloud and seal
// tests (leaned away from a wall where the straight approach meets it); then the order.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "approach_check.hpp"
#include "binpick/core/error.hpp"
#include "binpick/picking/picking.hpp"
#include "binpick/picking/tool_collision.hpp"
#include "grasp_candidates.hpp"
#include "pick_order.hpp"
#include "rigid.hpp"

namespace binpick::picking {
namespace {

// Detected poses are float refinements: rigid to ~1e-7, far inside this.
constexpr double kPoseTolerance = 1e-4;
// Ranks this close count as equal, so the grasp index and the wrist angle decide (1e-7 of the
// height term is 15 nm; symmetric copies differ by rounding only).
constexpr double kRankTie = 1e-7;

bool isValidPart(const DetectedPart& part) {
  return std::isfinite(part.score) && std::isfinite(part.coverage) && isRigidPose(part.T_base_model, kPoseTolerance);
}

bool isNearAvoided(const Eigen::Vector3d& centre, const std::vector<Eigen::Vector3d>& avoid, double radius) {
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

// How upright a bent nose's body stands (the z of its axis, base frame): a turn of the wrist
// moves it, and the more upright the body the further it keeps from the pile and the walls.
double bodyUpright(const Pick& pick, const GripperParams& gripper) {
  return (pick.T_base_grasp.linear() * gripper.bodyAxis()).z();
}

// A tie in rank (within kRankTie): the lower grasp index, then the more upright body of a bent
// nose, then the better wrist alignment; a full tie keeps the incumbent.
bool breaksTieBetter(const Pick& challenger, const Pick& incumbent, const GripperParams& gripper) {
  if (challenger.grasp != incumbent.grasp) return challenger.grasp < incumbent.grasp;
  if (gripper.bent()) {
    const double upright = bodyUpright(challenger, gripper) - bodyUpright(incumbent, gripper);
    if (std::abs(upright) > kRankTie) return upright > 0.0;
  }
  return wristAlignment(challenger.T_base_grasp) > wristAlignment(incumbent.T_base_grasp);
}

bool ranksBetter(const Pick& challenger, const Pick& incumbent, const GripperParams& gripper) {
  if (challenger.rank > incumbent.rank + kRankTie) return true;
  if (challenger.rank < incumbent.rank - kRankTie) return false;
  return breaksTieBetter(challenger, incumbent, gripper);
}

// The rank terms known without the measured cloud (RankWeights in picking.hpp).
double rankWithoutCloud(const DetectedPart& part, const Grasp& grasp, const Pick& pick, const PickParams& params) {
  const RankWeights& w = params.ranking;
  const Eigen::Vector3d in_bin = params.bin.T_base_bin.inverse() * pick.T_base_grasp.translation();
  return w.height * in_bin.z() / params.bin.wall_height + w.coverage * part.coverage +
         w.upright * (1.0 - pick.tilt_deg / 90.0) + w.quality * grasp.quality;
}

// How far a part's grasps got through the tests, in test order.
enum class Reached { Tilt, Bin, Cloud, Seal };

// A pick being tested, with the face pose it came from: the grasp as generated, before a lean
// away from a wall turned the approach (the cup seals on the face, not on the leaned disc).
struct Candidate {
  Pick pick;
  Eigen::Isometry3d T_base_face = Eigen::Isometry3d::Identity();
};

struct Screened {
  std::vector<Candidate> survivors;  // rank: the terms known without the cloud
  Reached furthest = Reached::Tilt;
};

// The approach corridor against the bin; where the tool meets a wall, the approach leaned away
// from it as far as the gripper allows. False when neither clears the bin and the tilt limit.
bool clearsBin(Pick& pick, const PickParams& params) {
  const Grasp& grasp = params.grasps[static_cast<std::size_t>(pick.grasp)];
  if (!approachHitsBin(pick.T_base_grasp, params, params.jawOpeningFor(grasp))) return true;
  const std::optional<Eigen::Isometry3d> leaned = leanClearOfWalls(pick.T_base_grasp, params);
  if (!leaned) return false;
  pick.lean_deg = angleDeg(pick.T_base_grasp.linear().col(2), leaned->linear().col(2));
  pick.T_base_grasp = *leaned;
  pick.tilt_deg = approachTiltDeg(pick.T_base_grasp);
  return pick.tilt_deg <= params.max_tilt_deg;
}

// A bent nose: the turns of one grasp that clear the bin, kept for the cloud test, the most
// upright first. More would multiply the cloud tests for turns that lean the body lower.
constexpr std::size_t kNoseTurnsKept = 3;

// The cheap tests: tilt, then the approach corridor against the bin (for a bent nose, turn by
// turn).
Screened screenCandidates(const DetectedPart& part, int object, const std::vector<GraspCandidate>& candidates,
                          const PickParams& params) {
  Screened screened;
  for (const GraspCandidate& candidate : candidates) {
    const Eigen::Isometry3d T_base_face = part.T_base_model * candidate.T_model_grasp;
    const double tilt_deg = approachTiltDeg(T_base_face);
    if (tilt_deg > params.max_tilt_deg) continue;
    screened.furthest = std::max(screened.furthest, Reached::Bin);
    // Whether the grasp, so turned, clears the bin: then it goes on to the cloud test.
    const auto screenTurn = [&](const Eigen::Isometry3d& T_base_turned) {
      Candidate tested;
      Pick& pick = tested.pick;
      pick.object = object;
      pick.grasp = candidate.grasp;
      pick.T_base_grasp = tested.T_base_face = T_base_turned;
      pick.tilt_deg = tilt_deg;
      if (!clearsBin(pick, params)) return false;
      screened.furthest = Reached::Cloud;
      pick.rank = rankWithoutCloud(part, params.grasps[static_cast<std::size_t>(pick.grasp)], pick, params);
      screened.survivors.push_back(tested);
      return true;
    };
    if (!params.gripper.bent()) {  // a straight tool's turn moves nothing
      screenTurn(T_base_face);
      continue;
    }
    std::size_t kept = 0;
    for (const Eigen::Isometry3d& T_base_turned : noseTurns(T_base_face, params)) {
      if (screenTurn(T_base_turned) && ++kept == kNoseTurnsKept) break;
    }
  }
  return screened;
}

// No measured cloud: nothing covers the part and the tool has all the clearance it can count.
std::optional<Pick> bestWithoutCloud(std::vector<Candidate> survivors, const PickParams& params) {
  std::optional<Pick> best;
  for (Candidate& candidate : survivors) {
    Pick& pick = candidate.pick;
    pick.clearance = params.clearance_cap;
    pick.rank += params.ranking.free + params.ranking.clearance;
    if (!best || ranksBetter(pick, *best, params.gripper)) best = pick;
  }
  return best;
}

ToolSweep sweepFor(const Grasp& grasp, const PickParams& params) {
  ToolSweep sweep;
  sweep.approach_distance = params.approach_distance;
  sweep.margin = params.collision_margin;
  sweep.opening = params.jawOpeningFor(grasp);
  sweep.clearance_cap = params.clearance_cap;
  return sweep;
}

// One part's queries of the measured scene, remembered per grasp point: the cover depends on the
// point alone, and a suction tool is round about its approach, so grasps differing only by a turn
// about it (a continuous symmetry about the approach axis) meet the cloud alike.
class PartCloudTests {
 public:
  PartCloudTests(const MeasuredScene& scene, const PickParams& params) : scene_(scene), params_(params) {}

  double covered(const Pick& pick) { return entryFor(pick).covered; }

  ToolContact contact(const Pick& pick) {
    const Grasp& grasp = params_.grasps[static_cast<std::size_t>(pick.grasp)];
    const auto query = [&] {
      return toolCollision(scene_, pick.T_base_grasp, params_.gripper, sweepFor(grasp, params_));
    };
    // Jaws and a bent nose are not round about the approach: their turn matters.
    if (params_.gripper.type != GripperType::Suction || params_.gripper.bent()) return query();
    Entry& entry = entryFor(pick);
    if (!entry.contact) entry.contact = query();
    return *entry.contact;
  }

 private:
  struct Entry {
    Eigen::Vector3d point, approach;
    double covered = 0.0;
    std::optional<ToolContact> contact;
  };

  Entry& entryFor(const Pick& pick) {
    const Eigen::Vector3d point = pick.T_base_grasp.translation();
    const Eigen::Vector3d approach = pick.T_base_grasp.linear().col(2);
    for (Entry& entry : entries_) {
      if ((entry.point - point).norm() < kSameAxis && (entry.approach - approach).norm() < kSameAxis) return entry;
    }
    const double covered = scene_.shareCoveredAbove(point, params_.cover_radius, params_.cover_height);
    entries_.push_back({point, approach, covered, std::nullopt});
    return entries_.back();
  }

  static constexpr double kSameAxis = 1e-9;  // metres, and for the unit approach vector
  const MeasuredScene& scene_;
  const PickParams& params_;
  std::vector<Entry> entries_;
};

// A suction cup must find a face under its whole disc in the measured cloud (seal_check.hpp),
// where it is or slid along the face by up to seal_check.max_shift (the pick then moves with it,
// keeping its lean: within the collision margin of where the tool was tested); jaws and a plan
// without the organized cloud skip the test.
bool sealsOnSurface(Candidate& candidate, const PickParams& params, const MeasuredSurface* surface) {
  if (!surface || params.gripper.type != GripperType::Suction) return true;
  const GripperParams& g = params.gripper;
  // The measured surface against the face's normal: the lean comes on top of what it allows.
  SealCheckParams check = params.seal_check;
  check.max_angle_deg = std::max(0.0, check.max_angle_deg - candidate.pick.lean_deg);
  const auto sealed = surface->findSeal(candidate.T_base_face, 0.5 * g.cup_diameter, g.seal_tolerance, check);
  if (sealed) candidate.pick.T_base_grasp = *sealed * (candidate.T_base_face.inverse() * candidate.pick.T_base_grasp);
  return sealed.has_value();
}

// Branch and bound in the order of the rank known without the cloud: the cover and clearance
// terms add at most free + clearance weight, so once a candidate cannot reach the best full rank
// neither can any after it. The result equals testing every candidate; usually the first
// collision-free one ends the search.
std::optional<Pick> bestAgainstCloud(std::vector<Candidate> survivors, const PickParams& params,
                                     const MeasuredScene& scene, const MeasuredSurface* surface, Reached& furthest) {
  std::stable_sort(survivors.begin(), survivors.end(),
                   [](const Candidate& a, const Candidate& b) { return a.pick.rank > b.pick.rank; });
  const RankWeights& w = params.ranking;
  PartCloudTests tests(scene, params);
  std::optional<Pick> best;
  for (Candidate& candidate : survivors) {
    Pick& pick = candidate.pick;
    if (best && pick.rank + w.free + w.clearance < best->rank - kRankTie) break;
    const double without_clearance = pick.rank + w.free * (1.0 - tests.covered(pick));
    if (best && without_clearance + w.clearance < best->rank - kRankTie) continue;
    const ToolContact contact = tests.contact(pick);
    if (contact.collision) continue;
    furthest = std::max(furthest, Reached::Seal);
    if (!sealsOnSurface(candidate, params, surface)) continue;
    pick.clearance = contact.clearance;
    pick.rank = without_clearance + w.clearance * contact.clearance / params.clearance_cap;
    if (!best || ranksBetter(pick, *best, params.gripper)) best = pick;
  }
  return best;
}

void countRejection(Reached furthest, PickRejections& rejected) {
  switch (furthest) {
    case Reached::Tilt: ++rejected.tilt; break;
    case Reached::Bin: ++rejected.bin; break;
    case Reached::Cloud: ++rejected.cloud; break;
    case Reached::Seal: ++rejected.seal; break;
  }
}

}  // namespace

PickPlan planPicks(const std::vector<DetectedPart>& parts, const std::vector<Eigen::Vector3d>& avoid,
                   const PickParams& params, const MeasuredScene* scene, const MeasuredSurface* surface) {
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
    Screened screened = screenCandidates(part, static_cast<int>(i), candidates, params);
    const std::optional<Pick> pick =
        scene ? bestAgainstCloud(std::move(screened.survivors), params, *scene, surface, screened.furthest)
              : bestWithoutCloud(std::move(screened.survivors), params);
    if (pick) {
      plan.picks.push_back(*pick);
    } else {
      countRejection(screened.furthest, plan.rejected);
    }
  }
  sortPicks(plan.picks, parts, params.order);
  return plan;
}

namespace {

const std::string kOwner = "picking";
// Configured poses and rotations come from text with a few decimals: looser than double rounding.
constexpr double kConfigTolerance = 1e-5;

void validateGrasps(const std::vector<Grasp>& grasps) {
  core::requireField(!grasps.empty(), kOwner, "grasps", "at least one grasp", grasps.size());
  for (const Grasp& grasp : grasps) {
    core::requireField(isRigidPose(grasp.T_model_grasp, kConfigTolerance), kOwner, "grasps", "finite rigid poses",
                       grasp.name);
    core::requireField(grasp.quality >= 0.0 && grasp.quality <= 1.0, kOwner, "grasps", "of quality in [0, 1]",
                       grasp.name);
    core::requireField(isNonNegative(grasp.width), kOwner, "grasps", "of width >= 0", grasp.name);
  }
}

void validateSymmetry(const PartSymmetry& symmetry) {
  const auto& discrete = symmetry.discrete;
  core::requireField(!discrete.empty(), kOwner, "symmetry.discrete", "non-empty", "none");
  bool holds_identity = false;
  for (std::size_t i = 0; i < discrete.size(); ++i) {
    core::requireField(isRotation(discrete[i], kConfigTolerance), kOwner, "symmetry.discrete", "rotations",
                       "entry " + std::to_string(i));
    holds_identity |= discrete[i].isApprox(Eigen::Matrix3d::Identity(), kConfigTolerance);
  }
  core::requireField(holds_identity, kOwner, "symmetry.discrete", "holding the identity", "none");
  if (symmetry.continuous_axis) {
    const double length = symmetry.continuous_axis->norm();
    core::requireField(std::isfinite(length) && length > 1e-9, kOwner, "symmetry.continuous_axis",
                       "a finite non-zero vector", length);
  }
}

void validateBin(const BinBox& bin) {
  core::requireField(isRigidPose(bin.T_base_bin, kConfigTolerance), kOwner, "bin.T_base_bin", "a finite rigid pose",
                     "not one");
  core::requireField(isPositive(bin.length), kOwner, "bin.length", "> 0", bin.length);
  core::requireField(isPositive(bin.width), kOwner, "bin.width", "> 0", bin.width);
  core::requireField(isPositive(bin.wall_height), kOwner, "bin.wall_height", "> 0", bin.wall_height);
}

}  // namespace

void RankWeights::validate() const {
  const std::string owner = kOwner + ".ranking";
  core::requireField(isNonNegative(free), owner, "free", ">= 0", free);
  core::requireField(isNonNegative(height), owner, "height", ">= 0", height);
  core::requireField(isNonNegative(coverage), owner, "coverage", ">= 0", coverage);
  core::requireField(isNonNegative(upright), owner, "upright", ">= 0", upright);
  core::requireField(isNonNegative(clearance), owner, "clearance", ">= 0", clearance);
  core::requireField(isNonNegative(quality), owner, "quality", ">= 0", quality);
}

PickOrder pickOrderFromName(const std::string& name) {
  if (name == "highest_first") return PickOrder::HighestFirst;
  if (name == "best_score") return PickOrder::BestScore;
  if (name == "best_rank") return PickOrder::BestRank;
  throw core::Error("unknown pick order \"" + name + "\" (use highest_first, best_score or best_rank)");
}

void PickParams::validate() const {
  validateGrasps(grasps);
  validateSymmetry(symmetry);
  validateBin(bin);
  core::requireField(isNonNegative(approach_distance), kOwner, "approach_distance", ">= 0", approach_distance);
  gripper.validate();
  core::requireField(isNonNegative(wall_clearance), kOwner, "wall_clearance", ">= 0", wall_clearance);
  core::requireField(max_tilt_deg >= 0 && max_tilt_deg <= 180, kOwner, "max_tilt_deg", "in [0, 180]", max_tilt_deg);
  // The upper bound keeps a typo from multiplying the candidates (and the plan time) unboundedly.
  core::requireField(continuous_symmetry_steps >= 1 && continuous_symmetry_steps <= 3600, kOwner,
                     "continuous_symmetry_steps", "in [1, 3600]", continuous_symmetry_steps);
  core::requireField(isNonNegative(avoid_radius), kOwner, "avoid_radius", ">= 0", avoid_radius);
  core::requireField(isNonNegative(collision_margin), kOwner, "collision_margin", ">= 0", collision_margin);
  core::requireField(isNonNegative(finger_clearance), kOwner, "finger_clearance", ">= 0", finger_clearance);
  core::requireField(isPositive(clearance_cap), kOwner, "clearance_cap", "> 0", clearance_cap);
  core::requireField(isNonNegative(cover_radius), kOwner, "cover_radius", ">= 0", cover_radius);
  core::requireField(isNonNegative(cover_height), kOwner, "cover_height", ">= 0", cover_height);
  ranking.validate();
  seal_check.validate();
}

}  // namespace binpick::picking
