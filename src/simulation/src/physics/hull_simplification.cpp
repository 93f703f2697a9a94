#include "hull_simplification.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace binpick::simulation::detail {
namespace {

// The vertices farthest along the 26 directions to the faces, edges and corners of a cube: a
// start that already spans the piece.
std::vector<std::size_t> extremeVertices(const std::vector<Eigen::Vector3d>& vertices) {
  std::vector<std::size_t> chosen;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const Eigen::Vector3d direction(dx, dy, dz);
        std::size_t best = 0;
        for (std::size_t v = 1; v < vertices.size(); ++v) {
          if (direction.dot(vertices[v]) > direction.dot(vertices[best])) best = v;
        }
        chosen.push_back(best);
      }
    }
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

// How far `point` lies outside `hull` (negative inside).
double distanceOutside(const ConvexHull& hull, const Eigen::Vector3d& point) {
  double outside = -std::numeric_limits<double>::infinity();
  for (const HullPlane& plane : hull.planes) {
    outside = std::max(outside, plane.normal.dot(point) - plane.offset);
  }
  return outside;
}

}  // namespace

std::vector<Eigen::Vector3d> simplifiedHullVertices(const ConvexHull& hull, double tolerance,
                                                    std::size_t max_vertices) {
  const std::vector<Eigen::Vector3d>& all = hull.vertices;
  if (all.size() <= max_vertices || hull.planes.empty()) return all;
  std::vector<Eigen::Vector3d> kept;
  for (const std::size_t v : extremeVertices(all)) kept.push_back(all[v]);
  while (kept.size() < all.size()) {
    const ConvexHull simple = convexHull(kept);
    if (simple.planes.empty()) return all;  // the start spans no volume: keep everything
    std::size_t farthest = 0;
    double distance = -std::numeric_limits<double>::infinity();
    for (std::size_t v = 0; v < all.size(); ++v) {
      const double d = distanceOutside(simple, all[v]);
      if (d > distance) {
        distance = d;
        farthest = v;
      }
    }
    if (distance <= tolerance) break;
    kept.push_back(all[farthest]);
  }
  return kept;
}

}  // namespace binpick::simulation::detail
