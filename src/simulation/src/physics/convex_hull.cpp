#include "convex_hull.hpp"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <limits>

namespace binpick::simulation::detail {
namespace {

// Newell's normal of a planar polygon: robust for the many-sided faces of a hull.
Eigen::Vector3d polygonNormal(const std::vector<Eigen::Vector3d>& corners) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < corners.size(); ++k) normal += corners[k].cross(corners[(k + 1) % corners.size()]);
  return normal;
}

}  // namespace

// The computer works on the points rounded to a fixed-point grid (about 1e-4 of the extent), and
// its topology is that of the rounded points. The hull keeps the input points as vertices; the
// face planes take their normals from the rounded corners (a sliver face's normal computed from
// the unrounded ones can point anywhere) and are pushed out by the largest rounding, so that every
// vertex lies inside every plane.
ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points) {
  ConvexHull hull;
  if (points.empty()) return hull;
  btConvexHullComputer computer;
  computer.compute(points.front().data(), static_cast<int>(sizeof(Eigen::Vector3d)), static_cast<int>(points.size()),
                   0.0, 0.0);
  std::vector<Eigen::Vector3d> rounded;
  double rounding = 0.0;
  for (int v = 0; v < computer.vertices.size(); ++v) {
    const btVector3& r = computer.vertices[v];
    rounded.emplace_back(r.x(), r.y(), r.z());
    hull.vertices.push_back(points[computer.original_vertex_index[v]]);
    hull.box.extend(hull.vertices.back());
    rounding = std::max(rounding, (rounded.back() - hull.vertices.back()).norm());
  }
  if (hull.vertices.size() < 4) return hull;
  // Relative to one vertex: the sums stay small and keep their precision.
  const Eigen::Vector3d reference = rounded.front();
  double six_volume = 0.0;
  std::vector<Eigen::Vector3d> corners;
  for (int f = 0; f < computer.faces.size(); ++f) {
    corners.clear();
    const btConvexHullComputer::Edge* first = &computer.edges[computer.faces[f]];
    const btConvexHullComputer::Edge* edge = first;
    do {  // counter-clockwise seen from outside
      corners.push_back(rounded[edge->getSourceVertex()] - reference);
      edge = edge->getNextEdgeOfFace();
    } while (edge != first);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) six_volume += corners[0].dot(corners[k].cross(corners[k + 1]));
    const Eigen::Vector3d normal = polygonNormal(corners);
    if (normal.norm() == 0.0) continue;
    const Eigen::Vector3d unit = normal.normalized();
    double offset = -std::numeric_limits<double>::infinity();
    for (const auto& c : corners) offset = std::max(offset, unit.dot(c));
    hull.planes.push_back({unit, offset + unit.dot(reference) + rounding});
  }
  hull.volume = six_volume / 6.0;
  if (hull.volume <= 0.0) hull.planes.clear();  // flat: no interior to describe
  return hull;
}

}  // namespace binpick::simulation::detail
