#include "approach_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "rigid.hpp"

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

// Leans tried, this far apart, up to the gripper's max_lean_deg.
constexpr double kLeanStepDeg = 1.0;

// Where the end of the tool body is at the pre-grasp point: on a tilted approach it swings out
// over a wall first.
Eigen::Vector3d toolEnd(const Eigen::Isometry3d& T_bin_grasp, const PickParams& params) {
  return T_bin_grasp * params.gripper.bodyEnd() - params.approach_distance * T_bin_grasp.linear().col(2);
}

// A bent nose's body, swept along the approach, fills a parallelogram grown by its radius: its
// edges are the body at the pre-grasp point and at the grasp, and the paths of its two ends. The
// bin's inside is convex, so the parallelogram clears it when every edge does. The slices that
// reach lowest are square to the body's axis, not to the approach.
bool bentBodyHitsBin(const Eigen::Isometry3d& T_bin_grasp, const PickParams& params) {
  const GripperParams& gripper = params.gripper;
  const Eigen::Vector3d sweep = params.approach_distance * T_bin_grasp.linear().col(2);
  const Eigen::Vector3d start = T_bin_grasp * gripper.bodyStart();
  const Eigen::Vector3d end = T_bin_grasp * gripper.bodyEnd();
  const Eigen::Vector3d axis = T_bin_grasp.linear() * -gripper.bodyAxis();
  const double radius = gripper.tool_radius + params.wall_clearance;
  const std::array<Segment, 4> edges{Segment{start, end}, Segment{start - sweep, end - sweep},
                                     Segment{start - sweep, start}, Segment{end - sweep, end}};
  for (const Segment& edge : edges) {
    if (corridorHitsFloor(edge) || corridorHitsWalls(edge, axis, radius, params.bin)) return true;
  }
  return false;
}

// Parallel jaws: each finger, `opening` apart from the other, is a corridor of its own from its tip
// back to where it was at the pre-grasp point, as wide as the finger's cross-section.
bool fingersHitBin(const Eigen::Isometry3d& T_bin_grasp, const PickParams& params, double opening) {
  const GripperParams& gripper = params.gripper;
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2), closing = T_bin_grasp.linear().col(0);
  const double radius = 0.5 * std::hypot(gripper.finger_thickness, gripper.finger_width) + params.wall_clearance;
  for (const double side : {1.0, -1.0}) {
    const Eigen::Vector3d centre =
        T_bin_grasp.translation() + side * (0.5 * opening + 0.5 * gripper.finger_thickness) * closing;
    const Segment finger{centre - (0.5 * gripper.finger_depth + params.approach_distance) * approach,
                         centre + 0.5 * gripper.finger_depth * approach};
    if (corridorHitsFloor(finger) || corridorHitsWalls(finger, approach, radius, params.bin)) return true;
  }
  return false;
}

// approachHitsBin in the bin frame.
bool toolHitsBin(const Eigen::Isometry3d& T_bin_grasp, const PickParams& params, double opening) {
  const Eigen::Vector3d grasp_point = T_bin_grasp.translation();
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2);
  const GripperParams& gripper = params.gripper;
  // The whole tool, from the end of its body at the pre-grasp point down to the grasp.
  const Eigen::Vector3d tool_end = toolEnd(T_bin_grasp, params);
  if (corridorHitsFloor({tool_end, grasp_point})) return true;
  const double body_radius = gripper.tool_radius + params.wall_clearance;
  if (gripper.type != GripperType::Suction) {
    return corridorHitsWalls({tool_end, grasp_point}, approach, body_radius, params.bin) ||
           fingersHitBin(T_bin_grasp, params, gripper.jawOpening(opening));
  }
  // A suction cup is narrower than the body behind it: a part lying by a wall is in the cup's
  // reach while the body stays clear higher up. A straight body's sweep also covers where the cup
  // passed; a bent one's does not.
  const double cup_radius = 0.5 * gripper.cup_diameter + params.wall_clearance;
  const Eigen::Vector3d cup_back = grasp_point - gripper.cup_length * approach;
  if (gripper.bent()) {
    const Eigen::Vector3d cup_start = cup_back - params.approach_distance * approach;
    return corridorHitsWalls({cup_start, grasp_point}, approach, cup_radius, params.bin) ||
           bentBodyHitsBin(T_bin_grasp, params);
  }
  return corridorHitsWalls({cup_back, grasp_point}, approach, cup_radius, params.bin) ||
         corridorHitsWalls({tool_end, cup_back}, approach, std::max(body_radius, cup_radius), params.bin);
}

// Away from the walls the tool comes too close to, each by how far it reaches past its limit, at
// the grasp point and at the end of the tool: beside one wall straight away from it, in a corner
// along the diagonal. Unit and square to the approach (only a turn of the approach moves the
// tool); none when no wall is near.
std::optional<Eigen::Vector3d> awayFromWalls(const Eigen::Isometry3d& T_bin_grasp, const PickParams& params) {
  const double reach = params.gripper.tool_radius + params.wall_clearance;
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2);
  Eigen::Vector3d inward = Eigen::Vector3d::Zero();
  const std::array<Eigen::Vector3d, 2> ends{T_bin_grasp.translation(), toolEnd(T_bin_grasp, params)};
  for (const Eigen::Vector3d& point : ends) {
    inward.x() -= std::copysign(std::max(0.0, std::abs(point.x()) - (0.5 * params.bin.length - reach)), point.x());
    inward.y() -= std::copysign(std::max(0.0, std::abs(point.y()) - (0.5 * params.bin.width - reach)), point.y());
  }
  inward -= inward.dot(approach) * approach;
  if (inward.norm() < 1e-9) return std::nullopt;
  return inward.normalized();
}

}  // namespace

double approachTiltDeg(const Eigen::Isometry3d& T_base_grasp) {
  return angleDeg(T_base_grasp.linear().col(2), Eigen::Vector3d(0.0, 0.0, -1.0));
}

bool approachHitsBin(const Eigen::Isometry3d& T_base_grasp, const PickParams& params, double opening) {
  return toolHitsBin(params.bin.T_base_bin.inverse() * T_base_grasp, params, opening);
}

std::optional<Eigen::Isometry3d> leanClearOfWalls(const Eigen::Isometry3d& T_base_grasp, const PickParams& params) {
  const GripperParams& gripper = params.gripper;
  if (gripper.type != GripperType::Suction || !(gripper.max_lean_deg > 0.0)) return std::nullopt;
  const Eigen::Isometry3d T_bin_grasp = params.bin.T_base_bin.inverse() * T_base_grasp;
  const std::optional<Eigen::Vector3d> inward = awayFromWalls(T_bin_grasp, params);
  if (!inward) return std::nullopt;
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2);
  // Leaning the approach by theta towards -inward swings the tool's back towards +inward about
  // the grasp point; the smallest lean that clears keeps the cup squarest on its face.
  const int steps = static_cast<int>(std::ceil(gripper.max_lean_deg / kLeanStepDeg));
  for (int step = 1; step <= steps; ++step) {
    const double lean = std::min(gripper.max_lean_deg, step * kLeanStepDeg) * M_PI / 180.0;
    const Eigen::Vector3d leaned = (approach - std::tan(lean) * *inward).normalized();
    Eigen::Isometry3d T_bin_leaned = T_bin_grasp;
    T_bin_leaned.linear() = Eigen::Quaterniond::FromTwoVectors(approach, leaned) * T_bin_grasp.linear();
    if (!toolHitsBin(T_bin_leaned, params, 0.0)) return params.bin.T_base_bin * T_bin_leaned;
  }
  return std::nullopt;
}

std::vector<Eigen::Isometry3d> noseTurns(const Eigen::Isometry3d& T_base_grasp, const PickParams& params) {
  const GripperParams& gripper = params.gripper;
  constexpr int kTurns = 12;
  // Equally upright turns (a vertical approach turns the body on a cone about it) within this.
  constexpr double kSameUpright = 1e-6;
  struct Turn {
    Eigen::Isometry3d T_base_grasp;
    double upright, off_centre;
  };
  const Eigen::Isometry3d T_bin_base = params.bin.T_base_bin.inverse();
  std::vector<Turn> turns;
  for (int step = 0; step < kTurns; ++step) {
    Eigen::Isometry3d turned = T_base_grasp;
    turned.linear() *= Eigen::AngleAxisd(2.0 * M_PI * step / kTurns, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d axis_in_bin = T_bin_base.linear() * turned.linear() * gripper.bodyAxis();
    const Eigen::Vector3d end_in_bin = T_bin_base * (turned * gripper.bodyEnd());
    turns.push_back({turned, axis_in_bin.z(), end_in_bin.head<2>().norm()});
  }
  std::stable_sort(turns.begin(), turns.end(), [](const Turn& a, const Turn& b) {
    if (std::abs(a.upright - b.upright) > kSameUpright) return a.upright > b.upright;
    return a.off_centre < b.off_centre;
  });
  std::vector<Eigen::Isometry3d> poses;
  for (const Turn& turn : turns) poses.push_back(turn.T_base_grasp);
  return poses;
}

}  // namespace binpick::picking
