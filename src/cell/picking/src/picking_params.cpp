#include <cmath>
#include <string>

#include "binpick/cell/picking.hpp"
#include "binpick/io/error.hpp"
#include "rigid.hpp"

namespace binpick::cell {
namespace {

const std::string kOwner = "picking";
// Configured poses and rotations come from text with a few decimals: looser than double rounding.
constexpr double kConfigTolerance = 1e-5;


void validateGrasps(const std::vector<Grasp>& grasps) {
  requireField(!grasps.empty(), kOwner, "grasps", "at least one grasp", grasps.size());
  for (const Grasp& grasp : grasps) {
    requireField(isRigidPose(grasp.T_model_grasp, kConfigTolerance), kOwner, "grasps",
                 "finite rigid poses", grasp.name);
    requireField(grasp.quality >= 0.0 && grasp.quality <= 1.0, kOwner, "grasps",
                 "of quality in [0, 1]", grasp.name);
    requireField(isNonNegative(grasp.width), kOwner, "grasps", "of width >= 0", grasp.name);
  }
}

void validateSymmetry(const PartSymmetry& symmetry) {
  const auto& discrete = symmetry.discrete;
  requireField(!discrete.empty(), kOwner, "symmetry.discrete", "non-empty", "none");
  bool holds_identity = false;
  for (std::size_t i = 0; i < discrete.size(); ++i) {
    requireField(isRotation(discrete[i], kConfigTolerance), kOwner, "symmetry.discrete",
                 "rotations", "entry " + std::to_string(i));
    holds_identity |= discrete[i].isApprox(Eigen::Matrix3d::Identity(), kConfigTolerance);
  }
  requireField(holds_identity, kOwner, "symmetry.discrete", "holding the identity", "none");
  if (symmetry.continuous_axis) {
    const double length = symmetry.continuous_axis->norm();
    requireField(std::isfinite(length) && length > 1e-9, kOwner, "symmetry.continuous_axis",
                 "a finite non-zero vector", length);
  }
}

void validateBin(const BinBox& bin) {
  requireField(isRigidPose(bin.T_base_bin, kConfigTolerance), kOwner, "bin.T_base_bin",
               "a finite rigid pose", "not one");
  requireField(isPositive(bin.length), kOwner, "bin.length", "> 0", bin.length);
  requireField(isPositive(bin.width), kOwner, "bin.width", "> 0", bin.width);
  requireField(isPositive(bin.wall_height), kOwner, "bin.wall_height", "> 0", bin.wall_height);
}

}  // namespace

void RankWeights::validate() const {
  const std::string owner = kOwner + ".ranking";
  requireField(isNonNegative(free), owner, "free", ">= 0", free);
  requireField(isNonNegative(height), owner, "height", ">= 0", height);
  requireField(isNonNegative(coverage), owner, "coverage", ">= 0", coverage);
  requireField(isNonNegative(upright), owner, "upright", ">= 0", upright);
  requireField(isNonNegative(clearance), owner, "clearance", ">= 0", clearance);
  requireField(isNonNegative(quality), owner, "quality", ">= 0", quality);
}

PickOrder pickOrderFromName(const std::string& name) {
  if (name == "highest_first") return PickOrder::HighestFirst;
  if (name == "best_score") return PickOrder::BestScore;
  if (name == "best_rank") return PickOrder::BestRank;
  throw Error("unknown pick order \"" + name + "\" (use highest_first, best_score or best_rank)");
}

void PickParams::validate() const {
  validateGrasps(grasps);
  validateSymmetry(symmetry);
  validateBin(bin);
  requireField(isNonNegative(approach_distance), kOwner, "approach_distance", ">= 0",
               approach_distance);
  gripper.validate();
  requireField(isNonNegative(wall_clearance), kOwner, "wall_clearance", ">= 0", wall_clearance);
  requireField(max_tilt_deg >= 0 && max_tilt_deg <= 180, kOwner, "max_tilt_deg", "in [0, 180]",
               max_tilt_deg);
  // The upper bound keeps a typo from multiplying the candidates (and the plan time) unboundedly.
  requireField(continuous_symmetry_steps >= 1 && continuous_symmetry_steps <= 3600, kOwner,
               "continuous_symmetry_steps", "in [1, 3600]", continuous_symmetry_steps);
  requireField(isNonNegative(avoid_radius), kOwner, "avoid_radius", ">= 0", avoid_radius);
  requireField(isNonNegative(collision_margin), kOwner, "collision_margin", ">= 0", collision_margin);
  requireField(isNonNegative(finger_clearance), kOwner, "finger_clearance", ">= 0", finger_clearance);
  requireField(isPositive(clearance_cap), kOwner, "clearance_cap", "> 0", clearance_cap);
  requireField(isNonNegative(cover_radius), kOwner, "cover_radius", ">= 0", cover_radius);
  requireField(isNonNegative(cover_height), kOwner, "cover_height", ">= 0", cover_height);
  ranking.validate();
  seal_check.validate();
}

}  // namespace binpick::cell
