#pragma once
// Is a grasp reachable: its approach tilt, and whether its approach corridor hits the bin.
#include <Eigen/Geometry>

#include "binpick/picking/picking.hpp"

namespace binpick::picking {

// Degrees between the grasp's approach (its z axis) and straight down (base -z), in [0, 180].
double approachTiltDeg(const Eigen::Isometry3d& T_base_grasp);

// Whether the corridor from the pre-grasp to the grasp point (picking.hpp) hits the bin's walls
// or floor. Analytic, no sampling: along the straight corridor the height and the lateral
// position change linearly, so the part of it low enough to meet a wall is one sub-segment and
// its extreme x and y lie at that sub-segment's ends.
bool approachHitsBin(const Eigen::Isometry3d& T_base_grasp, const PickParams& params);

}  // namespace binpick::picking
