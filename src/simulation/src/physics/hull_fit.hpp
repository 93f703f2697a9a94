#pragma once
// How well a convex piece fits the solid: the far cells (see solid_grid.hpp) whose centre lies
// inside the piece. Zero means the piece reaches at most about the far distance beyond the solid.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include "convex_hull.hpp"
#include "solid_grid.hpp"

namespace binpick::sim::detail {

// Visits each grid column under the hull once, cutting it with the hull's planes to an interval of
// heights, and counts that interval's far cells from the summed-volume table. Stops counting once
// the count exceeds `enough`: pass 0 to only ask whether the hull fits, LONG_MAX for the full count.
long farCellsInHull(const SolidGrid& solid, const ConvexHull& hull, long enough);

inline bool hullFits(const SolidGrid& solid, const ConvexHull& hull) {
  return farCellsInHull(solid, hull, 0) == 0;
}

}  // namespace binpick::sim::detail
