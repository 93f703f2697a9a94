#pragma once
// Convex decomposition of a closed mesh for collision shapes: convex pieces whose union contains
// the solid and reaches at most about `tolerance` beyond it. Recursively cuts the bounding box along
// cell borders (worst piece first) until every piece's hull fits, then joins neighbouring pieces
// whose joint hull still fits. Internal to binpick::simulation. Pure function: thread-safe.
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "convex_hull.hpp"

namespace binpick::simulation::detail {

struct ConvexDecomposition {
  std::vector<ConvexHull> pieces;  // model frame of the mesh
  double cell_size = 0.0;          // of the grid the fit was measured on
  double far_distance = 0.0;       // the tolerance actually checked (>= the one asked for)
  bool fits = false;               // every piece met the tolerance (false when max_pieces was too few)
};

ConvexDecomposition convexDecomposition(const io::TriangleMesh& mesh, double tolerance, int max_pieces);

}  // namespace binpick::simulation::detail
