#pragma once
// Whether a convex piece fits the solid: no far cell (see solid_grid.hpp) has its centre inside
// the piece, so the piece reaches at most about the far distance beyond the solid.
// Internal to binpick::simulation. Pure function: thread-safe.
#include "convex_hull.hpp"
#include "solid_grid.hpp"

namespace binpick::simulation::detail {

// Whether no far cell's centre lies inside the hull. Visits each grid column under the hull once,
// cutting it with the hull's planes to an interval of heights, and counts that interval's far
// cells from the summed-volume table; stops at the first.
bool hullFits(const SolidGrid& solid, const ConvexHull& hull);

}  // namespace binpick::simulation::detail
