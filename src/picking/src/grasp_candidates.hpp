#pragma once
// A part's candidate grasps: every configured grasp repeated over the part's symmetries.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/picking/picking.hpp"

namespace binpick::picking {

struct GraspCandidate {
  int grasp = 0;                                                    // index into PickParams::grasps
  Eigen::Isometry3d T_model_grasp = Eigen::Isometry3d::Identity();  // symmetry applied
};

// Every grasp G times every rotation C * S about the model origin: S each discrete symmetry, C
// each of continuous_symmetry_steps even turns about the continuous axis (the identity alone
// without one). Grouped by grasp, in grasp order; deterministic. Expects validated params.
std::vector<GraspCandidate> symmetricGraspCandidates(const PickParams& params);

}  // namespace binpick::picking
