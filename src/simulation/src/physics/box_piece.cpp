#include "box_piece.hpp"

#include <algorithm>

namespace binpick::simulation::detail {
namespace {

// Sutherland-Hodgman against one plane, both sides at once. Points on the plane go to both.
void clipPolygon(const SurfacePolygon& polygon, int axis, double position, std::vector<SurfacePolygon>& below,
                 std::vector<SurfacePolygon>& above) {
  SurfacePolygon low, high;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector3d& a = polygon[k];
    const Eigen::Vector3d& b = polygon[(k + 1) % polygon.size()];
    const double da = a[axis] - position, db = b[axis] - position;
    if (da <= 0.0) low.push_back(a);
    if (da >= 0.0) high.push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      Eigen::Vector3d crossing = a + (da / (da - db)) * (b - a);
      crossing[axis] = position;  // exactly on the plane, whatever the rounding
      low.push_back(crossing);
      high.push_back(crossing);
    }
  }
  if (!low.empty()) below.push_back(std::move(low));
  if (!high.empty()) above.push_back(std::move(high));
}

// Points of one side of a split: those strictly inside the side, and those on its boundary (the
// cut plane and the box corners).
struct SidePoints {
  std::vector<Eigen::Vector3d> interior, boundary;

  double hullVolume(std::size_t max_points) const {
    std::vector<Eigen::Vector3d> points = boundary;
    const std::size_t stride = 1 + interior.size() / std::max<std::size_t>(1, max_points);
    for (std::size_t k = 0; k < interior.size(); k += stride) points.push_back(interior[k]);
    return convexHull(points).volume;
  }
};

void addInsideCorners(const CellBox& box, const CellGrid& grid, const MeshColumns& columns,
                      std::vector<Eigen::Vector3d>& points) {
  const Eigen::Vector3d lo = box.min(grid), hi = box.max(grid);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                            (corner & 4) ? hi.z() : lo.z());
    if (columns.contains(p)) points.push_back(p);
  }
}

CellBox sideBox(const CellBox& box, int axis, int index, bool below) {
  CellBox side = box;
  (below ? side.hi : side.lo)[axis] = index;
  return side;
}

}  // namespace

std::vector<SurfacePolygon> meshPolygons(const io::TriangleMesh& mesh) {
  std::vector<SurfacePolygon> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    polygons.push_back(
        {mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(), mesh.vertices[t[2]].cast<double>()});
  }
  return polygons;
}

BoxPiece makeBoxPiece(const CellBox& box, std::vector<SurfacePolygon> polygons, const CellGrid& grid,
                      const MeshColumns& columns) {
  BoxPiece piece;
  piece.box = box;
  for (const auto& polygon : polygons) {
    piece.corners.insert(piece.corners.end(), polygon.begin(), polygon.end());
  }
  // A closed mesh repeats each vertex in about six triangles.
  const auto before = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(piece.corners.begin(), piece.corners.end(), before);
  piece.corners.erase(std::unique(piece.corners.begin(), piece.corners.end()), piece.corners.end());
  piece.polygons = std::move(polygons);
  std::vector<Eigen::Vector3d> points = piece.corners;
  addInsideCorners(box, grid, columns, points);
  piece.hull = convexHull(points);
  return piece;
}

BoxSplit splitBoxPiece(const BoxPiece& piece, int axis, int index, const CellGrid& grid, const MeshColumns& columns) {
  const double position = grid.border(axis, index);
  std::vector<SurfacePolygon> below, above;
  for (const auto& polygon : piece.polygons) clipPolygon(polygon, axis, position, below, above);
  return {makeBoxPiece(sideBox(piece.box, axis, index, true), std::move(below), grid, columns),
          makeBoxPiece(sideBox(piece.box, axis, index, false), std::move(above), grid, columns)};
}

SplitVolumes estimateSplitVolumes(const BoxPiece& piece, int axis, int index, const CellGrid& grid,
                                  const MeshColumns& columns, std::size_t max_points) {
  const double position = grid.border(axis, index);
  SidePoints below, above;
  for (const Eigen::Vector3d& p : piece.corners) {
    if (p[axis] < position) below.interior.push_back(p);
    if (p[axis] > position) above.interior.push_back(p);
    if (p[axis] == position) {
      below.boundary.push_back(p);
      above.boundary.push_back(p);
    }
  }
  for (const auto& polygon : piece.polygons) {
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const Eigen::Vector3d& a = polygon[k];
      const Eigen::Vector3d& b = polygon[(k + 1) % polygon.size()];
      const double da = a[axis] - position, db = b[axis] - position;
      if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
        Eigen::Vector3d crossing = a + (da / (da - db)) * (b - a);
        crossing[axis] = position;
        below.boundary.push_back(crossing);
        above.boundary.push_back(crossing);
      }
    }
  }
  addInsideCorners(sideBox(piece.box, axis, index, true), grid, columns, below.boundary);
  addInsideCorners(sideBox(piece.box, axis, index, false), grid, columns, above.boundary);
  return {below.hullVolume(max_points), above.hullVolume(max_points)};
}

}  // namespace binpick::simulation::detail
