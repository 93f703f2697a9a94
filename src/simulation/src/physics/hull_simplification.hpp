#pragma once
// Fewer vertices for a convex piece with many (a piece of a finely tessellated curved surface):
// Bullet's collision tests visit every vertex of a convex hull, so a piece with hundreds of them
// slows the whole simulation. Internal to binpick::simulation. Pure function: thread-safe.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "convex_hull.hpp"

namespace binpick::simulation::detail {

// A hull with more than `max_vertices` vertices comes back as a subset of them whose hull leaves
// no vertex more than `tolerance` outside it, found greedily: the farthest vertex outside joins
// next. Smaller hulls come back unchanged.
std::vector<Eigen::Vector3d> simplifiedHullVertices(const ConvexHull& hull, double tolerance, std::size_t max_vertices);

}  // namespace binpick::simulation::detail
