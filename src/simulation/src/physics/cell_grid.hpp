#pragma once
// A regular grid of cubic cells and boxes of its cells: the geometry shared by the voxelised solid
// and the convex decomposition. Internal to binpick::simulation. Plain values: thread-safe to read.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace binpick::simulation::detail {

// Cell (i, j, k) spans origin + [i, i + 1) * cell_size along x, and so on; its centre is the
// sample the grid's flags describe.
struct CellGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double cell_size = 1.0;
  Eigen::Vector3i size = Eigen::Vector3i::Zero();

  double border(int axis, int index) const { return origin[axis] + index * cell_size; }
  double centre(int axis, int index) const { return origin[axis] + (index + 0.5) * cell_size; }
  Eigen::Vector3d centre(const Eigen::Vector3i& cell) const {
    return origin + (cell.cast<double>().array() + 0.5).matrix() * cell_size;
  }
  // The first cell whose centre is at or above `position` along `axis` (not clamped).
  int firstCentreAtOrAbove(int axis, double position) const {
    return static_cast<int>(std::ceil((position - origin[axis]) / cell_size - 0.5));
  }
  // The last cell whose centre is at or below `position` along `axis` (not clamped).
  int lastCentreAtOrBelow(int axis, double position) const {
    return static_cast<int>(std::floor((position - origin[axis]) / cell_size - 0.5));
  }
  long cellCount() const { return static_cast<long>(size.x()) * size.y() * size.z(); }
  long index(int i, int j, int k) const { return (static_cast<long>(k) * size.y() + j) * size.x() + i; }
};

// The cells [lo, hi) (half-open along each axis).
struct CellBox {
  Eigen::Vector3i lo = Eigen::Vector3i::Zero();
  Eigen::Vector3i hi = Eigen::Vector3i::Zero();

  bool empty() const { return (hi.array() <= lo.array()).any(); }
  Eigen::Vector3d min(const CellGrid& grid) const {
    return {grid.border(0, lo.x()), grid.border(1, lo.y()), grid.border(2, lo.z())};
  }
  Eigen::Vector3d max(const CellGrid& grid) const {
    return {grid.border(0, hi.x()), grid.border(1, hi.y()), grid.border(2, hi.z())};
  }
};

}  // namespace binpick::simulation::detail
