#pragma once
// Where to cut a box piece whose hull does not fit the solid: the axis-aligned cell border that
// leaves the least hull volume beyond the solid on its two sides (the concavity measure of
// volumetric convex decompositions). Internal to binpick::simulation. Pure function: thread-safe.
#include <optional>

#include "box_piece.hpp"
#include "solid_grid.hpp"

namespace binpick::simulation::detail {

// The best split found by a coarse scan of every axis refined around the best candidate, or none
// when no border has solid on both sides (the piece is a single cell thick along every axis).
std::optional<BoxSplit> bestSplit(const BoxPiece& piece, const SolidGrid& solid, const MeshColumns& columns);

}  // namespace binpick::simulation::detail
