#pragma once
// The grasp generator's inside: every place the gripper fits on the sampled surface (suction_grasps.cpp,
// parallel_grasps.cpp), before ranking and the symmetry-aware selection (grasp_generation.cpp).
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/picking/grasp_generation.hpp"
#include "surface_model.hpp"

namespace binpick::picking {

struct GraspProposal {
  Eigen::Isometry3d T_model_grasp = Eigen::Isometry3d::Identity();
  int patch = 0;        // the face it holds (suction) or first touches (parallel)
  double margin = 0.0;  // in [0, 1]: seal margin or finger contact share (grasp_generation.hpp)
  double width = 0.0;   // parallel: metres between the contacts (Grasp::width); suction: 0
  std::string where;    // e.g. "face +z", "faces +-x, 30.0 mm"
};

// Expect validated params and gripper.
std::vector<GraspProposal> proposeSuctionGrasps(const SurfaceModel& surface, const GripperParams& gripper,
                                                const GraspGenerationParams& params);
std::vector<GraspProposal> proposeParallelGrasps(const SurfaceModel& surface, const GripperParams& gripper,
                                                 const GraspGenerationParams& params);

// A unit vector perpendicular to the unit `direction`, chosen the same way every time: the model
// axis least aligned with it, made perpendicular.
Eigen::Vector3d perpendicularTo(const Eigen::Vector3d& direction);
// "+z" when the unit `direction` is within 10 degrees of a model axis, else "(0.71, 0.71, 0.00)".
std::string directionLabel(const Eigen::Vector3d& direction);

}  // namespace binpick::picking
