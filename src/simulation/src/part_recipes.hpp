#pragma once
// The built-in part recipes, shared by parts.cpp (the table) and the files that define them
// (parts_prismatic.cpp, parts_turned.cpp). Internal to binpick::simulation.
#include <array>
#include <initializer_list>
#include <vector>

#include "binpick/simulation/parts.hpp"

namespace binpick::simulation::detail {

// Profiles are easier to read and check in millimetres; meshes are in metres.
std::vector<Eigen::Vector2d> millimetres(std::initializer_list<std::array<double, 2>> points);

// The model frame of every part is at its volume centroid, so that poses (and the rotations of
// their symmetries) are about a point that does not depend on how the profile was drawn.
io::TriangleMesh centredOnVolumeCentroid(const io::TriangleMesh& mesh);

// Prismatic parts (parts_prismatic.cpp).
Part makeLBracket();
Part makeLBracketLong();
Part makeClamp();
Part makeGear();
Part makeSwitch();
Part makeBulge();

// Turned parts (parts_turned.cpp).
Part makeRingMagnet();

}  // namespace binpick::simulation::detail
