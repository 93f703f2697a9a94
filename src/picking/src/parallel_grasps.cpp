// Parallel-jaw grasps: two opposite faces no wider apart than the stroke, both finger contact
// rectangles on them, and the fingers' path and the tool body free of the part.
#include <cmath>
#include <cstdio>

#include "grasp_proposals.hpp"

namespace binpick::picking {
namespace {

constexpr int kContactColumns = 3;  // samples across the finger (y)
constexpr int kContactRows = 5;     // samples along the approach (z)
constexpr double kMinContactShare = 0.5;
constexpr double kMinWidth = 0.001;  // metres: thinner walls are not gripped across

// The share of one finger's contact rectangle (centred on the grasp frame's yz, at x = side *
// width / 2) that touches a face whose outward normal is side * x, within the tolerance.
double contactShare(const SurfaceModel& surface, const Eigen::Isometry3d& T_model_grasp, double width, double side,
                    const GripperParams& gripper, const GraspGenerationParams& params, double antipodal_cos) {
  const Eigen::Vector3d x = side * T_model_grasp.linear().col(0);
  const Eigen::Vector3d y = T_model_grasp.linear().col(1), z = T_model_grasp.linear().col(2);
  const double standoff = gripper.finger_thickness;  // the ray starts where the finger's back is
  int touching = 0;
  for (int column = 0; column < kContactColumns; ++column) {
    for (int row = 0; row < kContactRows; ++row) {
      const double across = gripper.finger_width * (column / (kContactColumns - 1.0) - 0.5);
      const double along = gripper.finger_depth * (row / (kContactRows - 1.0) - 0.5);
      const Eigen::Vector3d on_face = T_model_grasp.translation() + 0.5 * width * x + across * y + along * z;
      const auto hit = surface.castRay(on_face + standoff * x, -x, standoff + params.contact_tolerance);
      if (hit && std::abs(hit->distance - standoff) <= params.contact_tolerance &&
          hit->normal.dot(x) >= antipodal_cos) {
        ++touching;
      }
    }
  }
  return static_cast<double>(touching) / (kContactColumns * kContactRows);
}

// Part points inside a finger (on its way in along the approach, or closed) or the tool body.
bool gripperHitsPart(const SurfaceModel& surface, const Eigen::Isometry3d& T_model_grasp, double width,
                     const GripperParams& gripper, const GraspGenerationParams& params) {
  const Eigen::Isometry3d T_grasp_model = T_model_grasp.inverse();
  const double finger_inner = 0.5 * width + params.contact_tolerance;  // the contact face itself is not in the way
  const double finger_outer = 0.5 * width + gripper.finger_thickness;
  const double root = -0.5 * gripper.finger_depth;
  const double tool_end = root - gripper.tool_length;
  for (const Eigen::Vector3d& point : surface.obstaclePoints()) {
    const Eigen::Vector3d local = T_grasp_model * point;
    if (local.z() < tool_end) continue;
    const bool in_finger_path = local.z() <= -root && std::abs(local.x()) > finger_inner &&
                                std::abs(local.x()) < finger_outer && std::abs(local.y()) < 0.5 * gripper.finger_width;
    const bool in_tool = local.z() < root && local.head<2>().norm() < gripper.tool_radius;
    if (in_finger_path || in_tool) return true;
  }
  return false;
}

std::string facesLabel(const Eigen::Vector3d& closing, double width) {
  std::string axis = directionLabel(closing);
  if (axis.size() == 2) axis = "+-" + axis.substr(1);  // both faces: "+-x"
  char millimetres[32];
  std::snprintf(millimetres, sizeof millimetres, "%.1f mm", width * 1e3);
  return "faces " + axis + ", " + millimetres;
}

}  // namespace

std::vector<GraspProposal> proposeParallelGrasps(const SurfaceModel& surface, const GripperParams& gripper,
                                                 const GraspGenerationParams& params) {
  const double antipodal_cos = std::cos(params.max_antipodal_angle_deg * M_PI / 180.0);
  std::vector<GraspProposal> proposals;
  for (const SurfaceSample& sample : surface.samples()) {
    // Into the part from the sample: where it leaves is the opposite contact.
    const double start = 1e-6;
    const auto exit = surface.castRay(sample.point - start * sample.normal, -sample.normal, gripper.stroke);
    if (!exit || exit->normal.dot(-sample.normal) < antipodal_cos) continue;
    const double width = exit->distance + start;
    if (width < kMinWidth || width > gripper.stroke) continue;
    const Eigen::Vector3d closing = sample.normal;  // grasp x: from the far face to the sample's
    const Eigen::Vector3d centre = sample.point - 0.5 * width * closing;
    const Eigen::Vector3d u = perpendicularTo(closing), v = closing.cross(u);
    for (int k = 0; k < params.approach_directions; ++k) {
      const double angle = 2.0 * M_PI * k / params.approach_directions;
      const Eigen::Vector3d approach = std::cos(angle) * u + std::sin(angle) * v;
      GraspProposal proposal;
      proposal.T_model_grasp.linear() << closing, approach.cross(closing), approach;
      proposal.T_model_grasp.translation() = centre;
      const double near_share =
          contactShare(surface, proposal.T_model_grasp, width, 1.0, gripper, params, antipodal_cos);
      if (near_share < kMinContactShare) continue;
      const double far_share =
          contactShare(surface, proposal.T_model_grasp, width, -1.0, gripper, params, antipodal_cos);
      if (far_share < kMinContactShare) continue;
      if (gripperHitsPart(surface, proposal.T_model_grasp, width, gripper, params)) continue;
      proposal.margin = (std::min(near_share, far_share) - kMinContactShare) / (1.0 - kMinContactShare);
      proposal.patch = sample.patch;
      proposal.where = facesLabel(closing, width);
      proposal.width = width;
      proposals.push_back(proposal);
    }
  }
  return proposals;
}

}  // namespace binpick::picking
