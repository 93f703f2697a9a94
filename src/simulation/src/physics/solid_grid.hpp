#pragma once
// A closed mesh voxelised for the convex decomposition: per cell centre, whether it lies inside the
// solid, whether the surface passes through the cell, and whether the centre is "far": outside the
// solid with no surface point within the far distance. A convex piece is accurate when no far
// centre lies inside it. Counts over boxes of cells come from summed-volume tables in O(1).
// Internal to binpick::simulation. Read-only after construction: safe to share for reading.
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "cell_grid.hpp"
#include "mesh_columns.hpp"

namespace binpick::simulation::detail {

// Cells of `cell_size` over the mesh's bounding box with a margin of at least the far distance,
// shifted by an irrational share of a cell so that cell borders and centres practically never
// coincide with a mesh vertex's coordinate of a part drawn on a round grid.
CellGrid gridAroundMesh(const io::TriangleMesh& mesh, double cell_size, double far_distance);

class SolidGrid {
 public:
  SolidGrid(const io::TriangleMesh& mesh, const MeshColumns& columns, const CellGrid& grid, double far_distance);

  const CellGrid& grid() const { return grid_; }
  bool occupied(int i, int j, int k) const { return flags_[grid_.index(i, j, k)] & kOccupied; }

  long farCells(const CellBox& box) const { return far_.sum(box); }
  long insideCells(const CellBox& box) const { return inside_.sum(box); }

 private:
  // Counts of flagged cells over every box [0, i) x [0, j) x [0, k).
  class SummedVolume {
   public:
    void build(const CellGrid& grid, const std::vector<uint8_t>& flags, uint8_t flag);
    long sum(const CellBox& box) const;

   private:
    long at(int i, int j, int k) const {
      return table_[(static_cast<long>(k) * (size_.y() + 1) + j) * (size_.x() + 1) + i];
    }
    Eigen::Vector3i size_ = Eigen::Vector3i::Zero();
    std::vector<int32_t> table_;
  };

  static constexpr uint8_t kInside = 1, kOccupied = 2, kNear = 4, kFar = 8;

  void markInside(const MeshColumns& columns);
  void markNearSurface(const io::TriangleMesh& mesh, double far_distance);

  CellGrid grid_;
  std::vector<uint8_t> flags_;
  SummedVolume far_, inside_;
};

}  // namespace binpick::simulation::detail
