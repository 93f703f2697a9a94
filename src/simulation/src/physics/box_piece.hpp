#pragma once
// The part of a closed mesh's solid inside an axis-aligned box of grid cells, and its convex hull.
// The hull of (solid within box) is the hull of the surface clipped to the box plus the box corners
// that lie inside the solid: every other extreme point of that region lies on a clipped polygon.
// So the hulls of the boxes of a partition contain the whole solid, exactly.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include <Eigen/Core>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "cell_grid.hpp"
#include "convex_hull.hpp"
#include "mesh_columns.hpp"

namespace binpick::simulation::detail {

using SurfacePolygon = std::vector<Eigen::Vector3d>;

struct BoxPiece {
  CellBox box;
  std::vector<SurfacePolygon> polygons;  // the mesh surface within the box
  std::vector<Eigen::Vector3d> corners;  // of the polygons, each point once
  ConvexHull hull;                       // of the solid within the box
};

std::vector<SurfacePolygon> meshPolygons(const io::TriangleMesh& mesh);

// Builds the piece of `polygons` (already within `box`) and its hull.
BoxPiece makeBoxPiece(const CellBox& box, std::vector<SurfacePolygon> polygons, const CellGrid& grid,
                      const MeshColumns& columns);

// The two pieces on either side of the cell border below cell `index` along `axis`.
struct BoxSplit {
  BoxPiece below, above;
};
BoxSplit splitBoxPiece(const BoxPiece& piece, int axis, int index, const CellGrid& grid, const MeshColumns& columns);

// The hull volumes the two sides of that split would have, for comparing cuts cheaply: on a mesh
// with many vertices only about `max_points` of each side's surface points are used (every
// point on the cut plane and every box corner always), so the volumes are estimates then.
struct SplitVolumes {
  double below = 0.0, above = 0.0;
};
SplitVolumes estimateSplitVolumes(const BoxPiece& piece, int axis, int index, const CellGrid& grid,
                                  const MeshColumns& columns, std::size_t max_points);

}  // namespace binpick::simulation::detail
