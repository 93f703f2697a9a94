#include "grasp_candidates.hpp"

#include <cmath>

namespace binpick::picking {
namespace {

// The turns about the continuous axis, the identity first; only the identity without an axis.
std::vector<Eigen::Matrix3d> continuousTurns(const PickParams& params) {
  const auto& axis = params.symmetry.continuous_axis;
  if (!axis) return {Eigen::Matrix3d::Identity()};
  const Eigen::Vector3d unit_axis = axis->normalized();
  const int steps = params.continuous_symmetry_steps;
  std::vector<Eigen::Matrix3d> turns;
  turns.reserve(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) {
    const double angle = 2.0 * M_PI * k / steps;
    turns.push_back(Eigen::AngleAxisd(angle, unit_axis).toRotationMatrix());
  }
  return turns;
}

}  // namespace

std::vector<GraspCandidate> symmetricGraspCandidates(const PickParams& params) {
  const std::vector<Eigen::Matrix3d> turns = continuousTurns(params);
  const auto& discrete = params.symmetry.discrete;
  std::vector<GraspCandidate> candidates;
  candidates.reserve(params.grasps.size() * turns.size() * discrete.size());
  for (std::size_t g = 0; g < params.grasps.size(); ++g) {
    for (const Eigen::Matrix3d& turn : turns) {
      for (const Eigen::Matrix3d& symmetry : discrete) {
        // A rotation about the model origin: a linear part only, no translation.
        Eigen::Isometry3d part_onto_itself = Eigen::Isometry3d::Identity();
        part_onto_itself.linear() = turn * symmetry;
        const Eigen::Isometry3d T_model_grasp = part_onto_itself * params.grasps[g].T_model_grasp;
        candidates.push_back({static_cast<int>(g), T_model_grasp});
      }
    }
  }
  return candidates;
}

}  // namespace binpick::picking
