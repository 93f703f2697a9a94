#include "solid_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../mesh_geometry.hpp"

namespace binpick::simulation::detail {
namespace {

// 2 - golden ratio: far from every simple fraction, so no round-number coordinate of a part lands
// on a cell border or centre.
constexpr double kGridShift = 0.3819660112501051;

}  // namespace

CellGrid gridAroundMesh(const io::TriangleMesh& mesh, double cell_size, double far_distance) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v.cast<double>());
    hi = hi.cwiseMax(v.cast<double>());
  }
  // Room for far cells all around, so that a piece bulging out of the bounding box is caught.
  const double margin = far_distance + 2.0 * cell_size;
  CellGrid grid;
  grid.cell_size = cell_size;
  grid.origin = lo - Eigen::Vector3d::Constant(margin + kGridShift * cell_size);
  for (int axis = 0; axis < 3; ++axis) {
    grid.size[axis] = static_cast<int>(std::ceil((hi[axis] + margin - grid.origin[axis]) / cell_size));
  }
  return grid;
}

SolidGrid::SolidGrid(const io::TriangleMesh& mesh, const MeshColumns& columns, const CellGrid& grid,
                     double far_distance)
    : grid_(grid), flags_(static_cast<std::size_t>(grid.cellCount()), 0) {
  markInside(columns);
  markNearSurface(mesh, far_distance);
  for (auto& f : flags_) {
    if (f & kInside) f |= kOccupied;
    if (!(f & (kInside | kNear))) f |= kFar;
  }
  far_.build(grid_, flags_, kFar);
  inside_.build(grid_, flags_, kInside);
}

void SolidGrid::markInside(const MeshColumns& columns) {
  for (int j = 0; j < grid_.size.y(); ++j) {
    for (int i = 0; i < grid_.size.x(); ++i) {
      const std::vector<double> heights = columns.crossings(grid_.centre(0, i), grid_.centre(1, j));
      std::size_t below = 0;  // crossings at or below the current centre
      for (int k = 0; k < grid_.size.z(); ++k) {
        const double z = grid_.centre(2, k);
        while (below < heights.size() && heights[below] <= z) ++below;
        if ((heights.size() - below) % 2 == 1) flags_[grid_.index(i, j, k)] |= kInside;
      }
    }
  }
}

// A centre within far_distance of a surface sample is within far_distance of the surface, so a
// centre marked near is never farther than that. Samples a cell apart leave only centres nearly
// that far unmarked: the test errs on the strict side.
void SolidGrid::markNearSurface(const io::TriangleMesh& mesh, double far_distance) {
  const double squared = far_distance * far_distance;
  const double h = grid_.cell_size;
  for (const Eigen::Vector3f& sample : surfaceSamples(mesh, h)) {
    const Eigen::Vector3d s = sample.cast<double>();
    Eigen::Vector3i lo, hi;
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = std::max(0, grid_.firstCentreAtOrAbove(axis, s[axis] - far_distance));
      hi[axis] = std::min(grid_.size[axis] - 1, grid_.lastCentreAtOrBelow(axis, s[axis] + far_distance));
    }
    for (int k = lo.z(); k <= hi.z(); ++k) {
      const double dz = grid_.centre(2, k) - s.z();
      for (int j = lo.y(); j <= hi.y(); ++j) {
        const double dy = grid_.centre(1, j) - s.y();
        const double room = squared - dz * dz - dy * dy;
        if (room < 0.0) continue;
        for (int i = lo.x(); i <= hi.x(); ++i) {
          const double dx = grid_.centre(0, i) - s.x();
          if (dx * dx <= room) flags_[grid_.index(i, j, k)] |= kNear;
        }
      }
    }
    const Eigen::Vector3i cell = ((s - grid_.origin) / h).array().floor().cast<int>().matrix();
    if ((cell.array() >= 0).all() && (cell.array() < grid_.size.array()).all())
      flags_[grid_.index(cell.x(), cell.y(), cell.z())] |= kOccupied;
  }
}

void SolidGrid::SummedVolume::build(const CellGrid& grid, const std::vector<uint8_t>& flags, uint8_t flag) {
  size_ = grid.size;
  const long nx = size_.x() + 1, ny = size_.y() + 1;
  table_.assign(static_cast<std::size_t>(nx * ny * (size_.z() + 1)), 0);
  const auto slot = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k < size_.z(); ++k)
    for (int j = 0; j < size_.y(); ++j)
      for (int i = 0; i < size_.x(); ++i)
        table_[slot(i + 1, j + 1, k + 1)] = (flags[grid.index(i, j, k)] & flag) ? 1 : 0;
  // Running sums along x, then y, then z turn cell flags into box counts.
  for (int k = 1; k <= size_.z(); ++k)
    for (int j = 1; j <= size_.y(); ++j)
      for (int i = 1; i <= size_.x(); ++i) table_[slot(i, j, k)] += table_[slot(i - 1, j, k)];
  for (int k = 1; k <= size_.z(); ++k)
    for (int j = 1; j <= size_.y(); ++j)
      for (int i = 1; i <= size_.x(); ++i) table_[slot(i, j, k)] += table_[slot(i, j - 1, k)];
  for (int k = 1; k <= size_.z(); ++k)
    for (int j = 1; j <= size_.y(); ++j)
      for (int i = 1; i <= size_.x(); ++i) table_[slot(i, j, k)] += table_[slot(i, j, k - 1)];
}

long SolidGrid::SummedVolume::sum(const CellBox& box) const {
  if (box.empty()) return 0;
  const Eigen::Vector3i& a = box.lo;
  const Eigen::Vector3i& b = box.hi;
  return at(b.x(), b.y(), b.z()) - at(a.x(), b.y(), b.z()) - at(b.x(), a.y(), b.z()) - at(b.x(), b.y(), a.z()) +
         at(a.x(), a.y(), b.z()) + at(a.x(), b.y(), a.z()) + at(b.x(), a.y(), a.z()) - at(a.x(), a.y(), a.z());
}

}  // namespace binpick::simulation::detail
