#pragma once
// Where the next layer of parts is released: random orientations and positions above the pile,
// every part's footprint between the walls, no two parts overlapping at the start.
// Internal to binpick::simulation. Pure function of its inputs and the generator's state.
#include <Eigen/Geometry>
#include <vector>

#include "../random.hpp"
#include "binpick/simulation/physics_pile.hpp"

namespace binpick::simulation::detail {

// Up to `wanted` poses T_bin_model (at least one): each part's lowest point is drop_height_min to
// drop_height_max above `pile_top`, its footprint at least `wall_clearance` inside the walls.
// `extreme_points` (model frame) give the part's extent. The layer ends early when a few random
// tries find no free place for the next part.
std::vector<Eigen::Isometry3d> releaseLayer(int wanted, double pile_top,
                                            const std::vector<Eigen::Vector3d>& extreme_points, const BinInterior& bin,
                                            const PhysicsParams& params, double wall_clearance, Rng& rng);

}  // namespace binpick::simulation::detail
