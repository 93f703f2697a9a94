#pragma once
// Is a grasp reachable: its approach tilt, and whether its approach corridor hits the bin.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "binpick/picking/picking.hpp"

namespace binpick::picking {

// Degrees between the grasp's approach (its z axis) and straight down (base -z), in [0, 180].
double approachTiltDeg(const Eigen::Isometry3d& T_base_grasp);

// Whether the corridor from the pre-grasp to the grasp point (picking.hpp) hits the bin's walls
// or floor. Analytic, no sampling: along the straight corridor the height and the lateral
// position change linearly, so the part of it low enough to meet a wall is one sub-segment and
// its extreme x and y lie at that sub-segment's ends.
// A suction tool is two corridors: the cup's (its radius) and the body's behind it; parallel jaws
// add one per finger, the fingers `opening` apart between their contact faces (0: the full stroke).
bool approachHitsBin(const Eigen::Isometry3d& T_base_grasp, const PickParams& params, double opening = 0.0);

// A suction grasp whose tool meets a wall, turned about its grasp point by the smallest lean (1
// degree steps, up to gripper.max_lean_deg) away from the walls it comes too close to whose
// corridor clears the bin; none when no lean does (or the gripper may not lean). The cup still
// sits on the same point of the face, its bellows taking up the lean.
std::optional<Eigen::Isometry3d> leanClearOfWalls(const Eigen::Isometry3d& T_base_grasp, const PickParams& params);

// Where a bent nose's body may lean (gripper.bent()): the grasp turned about its approach in
// twelve 30-degree steps, the body's most upright first (it leans back from a tilted face's
// normal towards vertical), then the one whose end keeps furthest in from the walls. (A straight
// tool's turn moves nothing: the planner tries its grasp as it is.)
std::vector<Eigen::Isometry3d> noseTurns(const Eigen::Isometry3d& T_base_grasp, const PickParams& params);

}  // namespace binpick::picking
