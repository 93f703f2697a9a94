#pragma once
// The bin as a mesh: a floor slab and four walls, each a closed box, in the bin frame (origin at
// the centre of the floor's top face, z up). Internal to binpick::simulation. Pure: thread-safe.
#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation::detail {

constexpr double kBinWallThickness = 0.010;   // metres
constexpr double kBinFloorThickness = 0.010;  // metres, below z = 0

// Inner size length (x) x width (y); walls rise from z = 0 to wall_height outside that area.
io::TriangleMesh makeBinMesh(double length, double width, double wall_height);

}  // namespace binpick::simulation::detail
