#include "mesh_columns.hpp"

#include <algorithm>
#include <array>
#include <optional>

namespace binpick::simulation::detail {
namespace {

using Point2 = Eigen::Vector2d;

bool lexicographicallyBefore(const Point2& u, const Point2& v) {
  return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y());
}

// Which side of the line through u and v the point q lies on: twice the signed area of
// (first, second, q) with the endpoints sorted, so that both triangles sharing an edge compute the
// very same number for q and agree on which side is positive.
double edgeSide(const Point2& u, const Point2& v, const Point2& q) {
  const Point2& a = lexicographicallyBefore(u, v) ? u : v;
  const Point2& b = lexicographicallyBefore(u, v) ? v : u;
  return (b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x());
}

// Height at which the vertical line through q crosses triangle abc, if it does. On a tie (q exactly
// on an edge's projection) the edge belongs to the triangle lying on its positive side, so a
// surface crossing the line through an edge counts once, and a fold counts twice or not at all.
std::optional<double> verticalHit(const std::array<Eigen::Vector3d, 3>& corner, const Point2& q) {
  std::array<double, 3> weight{};
  for (int k = 0; k < 3; ++k) {
    const Point2 u = corner[(k + 1) % 3].head<2>(), v = corner[(k + 2) % 3].head<2>();
    const double side = edgeSide(u, v, q);
    const double opposite = edgeSide(u, v, corner[k].head<2>());
    if (opposite == 0.0) return std::nullopt;  // seen edge-on from above
    const bool inside = side * opposite > 0.0 || (side == 0.0 && opposite > 0.0);
    if (!inside) return std::nullopt;
    weight[k] = side / opposite;  // barycentric coordinate of corner k
  }
  const double sum = weight[0] + weight[1] + weight[2];
  return (weight[0] * corner[0].z() + weight[1] * corner[1].z() + weight[2] * corner[2].z()) / sum;
}

int clampedCell(const CellGrid& grid, int axis, double position) {
  const int cell = static_cast<int>(std::floor((position - grid.origin[axis]) / grid.cell_size));
  return std::clamp(cell, 0, grid.size[axis] - 1);
}

}  // namespace

MeshColumns::MeshColumns(const io::TriangleMesh& mesh, const CellGrid& grid) : mesh_(mesh), grid_(grid) {
  const int buckets = grid.size.x() * grid.size.y();
  std::vector<Eigen::Vector4i> footprint;  // per triangle: x0, x1, y0, y1 (inclusive)
  footprint.reserve(mesh.triangles.size());
  std::vector<int> count(buckets + 1, 0);
  for (const auto& t : mesh.triangles) {
    const Point2 a = mesh.vertices[t[0]].head<2>().cast<double>();
    const Point2 b = mesh.vertices[t[1]].head<2>().cast<double>();
    const Point2 c = mesh.vertices[t[2]].head<2>().cast<double>();
    if (edgeSide(a, b, c) == 0.0) {  // seen edge-on from above: never crossed by a vertical line
      footprint.emplace_back(0, -1, 0, -1);
      continue;
    }
    const Point2 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    const Eigen::Vector4i f(clampedCell(grid, 0, lo.x()), clampedCell(grid, 0, hi.x()), clampedCell(grid, 1, lo.y()),
                            clampedCell(grid, 1, hi.y()));
    footprint.push_back(f);
    for (int j = f[2]; j <= f[3]; ++j)
      for (int i = f[0]; i <= f[1]; ++i) ++count[j * grid.size.x() + i + 1];
  }
  for (int b = 0; b < buckets; ++b) count[b + 1] += count[b];
  bucket_start_ = count;
  triangles_.resize(count[buckets]);
  for (std::size_t t = 0; t < footprint.size(); ++t) {
    const Eigen::Vector4i& f = footprint[t];
    for (int j = f[2]; j <= f[3]; ++j)
      for (int i = f[0]; i <= f[1]; ++i) triangles_[count[j * grid.size.x() + i]++] = int(t);
  }
}

int MeshColumns::bucketOf(double x, double y) const {
  return clampedCell(grid_, 1, y) * grid_.size.x() + clampedCell(grid_, 0, x);
}

std::vector<double> MeshColumns::crossings(double x, double y) const {
  std::vector<double> heights;
  const Point2 q(x, y);
  const int bucket = bucketOf(x, y);
  for (int n = bucket_start_[bucket]; n < bucket_start_[bucket + 1]; ++n) {
    const Eigen::Vector3i& t = mesh_.triangles[triangles_[n]];
    const std::array<Eigen::Vector3d, 3> corner{
        mesh_.vertices[t[0]].cast<double>(), mesh_.vertices[t[1]].cast<double>(), mesh_.vertices[t[2]].cast<double>()};
    if (const auto z = verticalHit(corner, q)) heights.push_back(*z);
  }
  std::sort(heights.begin(), heights.end());
  return heights;
}

bool MeshColumns::contains(const Eigen::Vector3d& point) const {
  const std::vector<double> heights = crossings(point.x(), point.y());
  const auto above = heights.end() - std::upper_bound(heights.begin(), heights.end(), point.z());
  return above % 2 == 1;
}

}  // namespace binpick::simulation::detail
