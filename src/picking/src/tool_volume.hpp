#pragma once
// The tool's volume in the grasp frame (z: the approach, into the part), as toolCollision tests
// it against the measured cloud (tool_collision.hpp says what each gripper's volume is): distances
// from a point to each piece, and the volume's bounding box in the base frame. Internal to
// binpick::picking. Plain data and pure functions: thread-safe.
#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "binpick/picking/gripper.hpp"
#include "binpick/picking/tool_collision.hpp"

namespace binpick::picking {

struct Cylinder {  // about the grasp z axis
  double radius = 0, z_lo = 0, z_hi = 0;
  bool front_is_contact = false;  // points in front of z_hi are the grasped face (clearance)
};

struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  double between_jaws = 0;  // points with |x| below this are the grasped part (clearance)
};

// A bent nose's body (gripper.hpp): a cylinder off the approach axis, from `start` along the unit
// `axis` for `length`, swept back along the approach (-z) by `sweep`.
struct BentBody {
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), axis = -Eigen::Vector3d::UnitZ();
  double radius = 0, length = 0, sweep = 0;
};

struct ToolVolume {
  std::array<Cylinder, 2> cylinders;
  std::array<Box, 2> boxes;
  int cylinder_count = 0, box_count = 0;
  std::optional<BentBody> bent_body;
};

// The gripper's volume, grown by the sweep's margin and swept back along the approach.
ToolVolume toolVolume(const GripperParams& gripper, const ToolSweep& sweep);

// Distance from `p` (grasp frame) to a cylinder or a box; negative when inside. `counts` tells
// whether the distance matters for the clearance (not for the grasped face, nor the part between
// the jaws).
double cylinderDistance(const Cylinder& c, const Eigen::Vector3d& p, bool& counts);
double boxDistance(const Box& b, const Eigen::Vector3d& p, bool& counts);
// Distance from `p` to a bent nose's swept body (negative inside), or `beyond` when it is at least
// that far.
double bentBodyDistance(const BentBody& body, const Eigen::Vector3d& p, double beyond);

// The tool's bounding box in the base frame, grown by `grow`.
void baseBounds(const ToolVolume& tool, const Eigen::Isometry3d& T_base_grasp, double grow, Eigen::Vector3d& lo,
                Eigen::Vector3d& hi);

}  // namespace binpick::picking
