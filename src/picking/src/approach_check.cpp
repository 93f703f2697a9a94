#include "approach_check.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace binpick::picking {
namespace {

struct Segment {
  Eigen::Vector3d from, to;
};

// The part of `segment` with z <= z_limit, if any (one piece: z is linear along it).
std::optional<Segment> partBelow(const Segment& segment, double z_limit) {
  const bool from_below = segment.from.z() <= z_limit;
  const bool to_below = segment.to.z() <= z_limit;
  if (from_below && to_below) return segment;
  if (!from_below && !to_below) return std::nullopt;
  // Exactly one end is above, so the heights differ and the crossing lies between them.
  const double t = (z_limit - segment.from.z()) / (segment.to.z() - segment.from.z());
  const Eigen::Vector3d crossing = segment.from + t * (segment.to - segment.from);
  if (from_below) return Segment{segment.from, crossing};
  return Segment{crossing, segment.to};
}

bool insideShrunkBox(const Eigen::Vector3d& point, double half_length, double half_width) {
  return std::abs(point.x()) <= half_length && std::abs(point.y()) <= half_width;
}

// The corridor, a cylinder of `radius` about `axis` (bin frame, unit direction `approach`), meets
// a wall where a slice of it reaches below the wall top with its axis point outside the inner box
// shrunk by the radius. A slice normal to an axis tilted by theta from vertical reaches
// radius * sin(theta) below its axis point, so every slice whose axis point lies below
// wall_height + that reach is checked. Shrinking by the full radius sideways is exact for a
// vertical corridor and on the safe side for a tilted one (its slices reach less far sideways).
bool corridorHitsWalls(const Segment& axis, const Eigen::Vector3d& approach, double radius, const BinBox& bin) {
  const double sin_tilt = std::sqrt(std::max(0.0, 1.0 - approach.z() * approach.z()));
  const std::optional<Segment> low = partBelow(axis, bin.wall_height + radius * sin_tilt);
  if (!low) return false;
  const double half_length = 0.5 * bin.length - radius;
  const double half_width = 0.5 * bin.width - radius;
  return !insideShrunkBox(low->from, half_length, half_width) || !insideShrunkBox(low->to, half_length, half_width);
}

// The grasp point may sit right above the floor (a flat part lying on it) and the tool face
// rests on the part there, so only the axis is kept above the floor: no radius, no clearance.
bool corridorHitsFloor(const Segment& axis) { return std::min(axis.from.z(), axis.to.z()) < 0.0; }

}  // namespace

double approachTiltDeg(const Eigen::Isometry3d& T_base_grasp) {
  const Eigen::Vector3d approach = T_base_grasp.linear().col(2);
  const Eigen::Vector3d down(0.0, 0.0, -1.0);
  // atan2 of sine and cosine stays accurate near 0 and 180 degrees, where acos is not.
  const double angle = std::atan2(approach.cross(down).norm(), approach.dot(down));
  return angle * 180.0 / M_PI;
}

bool approachHitsBin(const Eigen::Isometry3d& T_base_grasp, const PickParams& params) {
  const Eigen::Isometry3d T_bin_grasp = params.bin.T_base_bin.inverse() * T_base_grasp;
  const Eigen::Vector3d grasp_point = T_bin_grasp.translation();
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2);
  // The whole tool, from the end of its body at the pre-grasp point down to the grasp: on a tilted
  // approach the body's far end swings out over the wall first.
  const Segment axis{grasp_point - (params.approach_distance + params.gripper.toolBack()) * approach, grasp_point};
  const double radius = params.gripper.tool_radius + params.wall_clearance;
  return corridorHitsFloor(axis) || corridorHitsWalls(axis, approach, radius, params.bin);
}

}  // namespace binpick::picking
