#include "hull_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace binpick::simulation::detail {
namespace {

// The first and last cell (along z) of column (x, y) whose centre lies inside the hull; first >
// last when none does.
std::pair<int, int> cellsInColumn(const CellGrid& grid, const ConvexHull& hull, double x, double y) {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  for (const HullPlane& plane : hull.planes) {
    const double room = plane.offset - plane.normal.x() * x - plane.normal.y() * y;
    const double nz = plane.normal.z();
    if (std::abs(nz) < 1e-12) {
      if (room < 0.0) return {1, 0};
    } else if (nz > 0.0) {
      high = std::min(high, room / nz);
    } else {
      low = std::max(low, room / nz);
    }
    if (low > high) return {1, 0};
  }
  const int first = std::max(0, grid.firstCentreAtOrAbove(2, low));
  const int last = std::min(grid.size.z() - 1, grid.lastCentreAtOrBelow(2, high));
  return {first, last};
}

}  // namespace

bool hullFits(const SolidGrid& solid, const ConvexHull& hull) {
  if (hull.planes.empty()) return true;
  const CellGrid& grid = solid.grid();
  const int i0 = std::max(0, grid.firstCentreAtOrAbove(0, hull.box.min().x()));
  const int i1 = std::min(grid.size.x() - 1, grid.lastCentreAtOrBelow(0, hull.box.max().x()));
  const int j0 = std::max(0, grid.firstCentreAtOrAbove(1, hull.box.min().y()));
  const int j1 = std::min(grid.size.y() - 1, grid.lastCentreAtOrBelow(1, hull.box.max().y()));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const auto [first, last] = cellsInColumn(grid, hull, grid.centre(0, i), grid.centre(1, j));
      if (first > last) continue;
      const CellBox column{Eigen::Vector3i(i, j, first), Eigen::Vector3i(i + 1, j + 1, last + 1)};
      if (solid.farCells(column) > 0) return false;
    }
  }
  return true;
}

}  // namespace binpick::simulation::detail
