#pragma once
// Where vertical lines cross the surface of a closed mesh: the basis of inside/outside tests by
// ray parity. Triangles are bucketed by the grid columns their xy footprint overlaps, so a query
// only visits the triangles near its line. Internal to binpick::simulation. Read-only after
// construction: safe to query from several threads.
#include <Eigen/Core>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "cell_grid.hpp"

namespace binpick::simulation::detail {

class MeshColumns {
 public:
  // Buckets over the x, y cells of `grid` (which must cover the mesh). Keeps a reference to `mesh`.
  MeshColumns(const io::TriangleMesh& mesh, const CellGrid& grid);

  // Heights at which the vertical line through (x, y) crosses the surface, ascending. A line
  // through a shared edge counts the crossing once (the edge belongs to one of its triangles).
  std::vector<double> crossings(double x, double y) const;

  // Ray parity: an odd number of crossings above the point.
  bool contains(const Eigen::Vector3d& point) const;

 private:
  int bucketOf(double x, double y) const;

  const io::TriangleMesh& mesh_;
  CellGrid grid_;
  std::vector<int> bucket_start_;  // triangles of bucket b: triangles_[start[b], start[b + 1])
  std::vector<int> triangles_;
};

}  // namespace binpick::simulation::detail
