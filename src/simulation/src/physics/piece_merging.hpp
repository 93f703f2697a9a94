#pragma once
// Joins convex pieces of a decomposition: first every pair of neighbours whose joint hull still
// fits the solid (the pair adding the least volume first), then, while there are more than
// `max_pieces`, the pair adding the least volume whether it fits or not.
// Internal to binpick::simulation. Pure function: thread-safe.
#include <vector>

#include "convex_hull.hpp"
#include "solid_grid.hpp"

namespace binpick::simulation::detail {

std::vector<ConvexHull> mergePieces(std::vector<ConvexHull> pieces, const SolidGrid& solid, int max_pieces);

}  // namespace binpick::simulation::detail
