#pragma once
// Planar polygon helpers behind makePrism: validation and ear-clipping triangulation.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace binpick::simulation::detail {

using Polygon = std::vector<Eigen::Vector2d>;

// Twice the signed area: positive for a counter-clockwise polygon.
double twiceSignedArea(const Polygon& polygon);

// The profile made ready for triangulation: repeated and collinear vertices removed (they would
// create zero-area triangles) and the winding made counter-clockwise. Throws core::Error when
// fewer than 3 corners remain, the area is zero, a coordinate is not finite, or two edges cross.
Polygon cleanSimplePolygon(const Polygon& profile);

// Ear clipping of a simple counter-clockwise polygon without collinear vertices. Returns
// counter-clockwise triangles as indices into `polygon`; n - 2 of them.
std::vector<std::array<int, 3>> triangulateByEarClipping(const Polygon& polygon);

}  // namespace binpick::simulation::detail
