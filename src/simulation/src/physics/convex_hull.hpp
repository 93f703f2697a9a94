#pragma once
// Convex hulls of point sets (Bullet's exact hull computer) with their face planes and volume.
// Internal to binpick::simulation. Pure function: thread-safe.
#include <Eigen/Geometry>
#include <vector>

namespace binpick::simulation::detail {

struct HullPlane {
  Eigen::Vector3d normal;  // unit, outward
  double offset = 0.0;     // the hull is where normal . p <= offset
};

struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<HullPlane> planes;  // empty when the points span no volume
  double volume = 0.0;
  Eigen::AlignedBox3d box;  // of the vertices
};

ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points);

}  // namespace binpick::simulation::detail
