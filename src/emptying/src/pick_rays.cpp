#include "pick_rays.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::emptying::detail {
namespace {

int stepsOver(double length, double spacing) {
  return std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
}

}  // namespace

std::vector<Eigen::Vector2d> discSamples(double radius, double spacing) {
  std::vector<Eigen::Vector2d> points{Eigen::Vector2d::Zero()};
  const int rings = stepsOver(radius, spacing);
  for (int k = 1; k <= rings; ++k) {
    const double rho = radius * k / rings;
    const int around = std::max(6, stepsOver(2.0 * M_PI * rho, spacing));
    for (int i = 0; i < around; ++i) {
      const double angle = 2.0 * M_PI * i / around;
      points.emplace_back(rho * std::cos(angle), rho * std::sin(angle));
    }
  }
  return points;
}

std::vector<Eigen::Vector2d> rectangleSamples(double x0, double x1, double y0, double y1, double spacing) {
  const int nx = stepsOver(x1 - x0, spacing), ny = stepsOver(y1 - y0, spacing);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      points.emplace_back(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny);
    }
  }
  return points;
}

SweepHit sweepHits(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp, const std::vector<Column>& columns) {
  const Eigen::Vector3d approach = T_bin_grasp.linear().col(2);
  std::vector<simulation::Ray> rays;
  rays.reserve(columns.size());
  for (const Column& column : columns) {
    if (!(column.z_to > column.z_from)) continue;
    simulation::Ray ray;
    ray.origin = T_bin_grasp * Eigen::Vector3d(column.xy.x(), column.xy.y(), column.z_from);
    ray.direction = approach;
    ray.t_max = column.z_to - column.z_from;
    rays.push_back(ray);
  }
  for (const simulation::RayHit& hit : scene.caster().closestHits(rays)) {
    if (hit.hit()) return {true, hit.object_id};
  }
  return {};
}

std::string hitReason(const std::string& solid, int object) {
  if (object == PickJudgement::kBin) return solid + " hits the bin";
  return solid + " hits part " + std::to_string(object);
}

std::vector<simulation::RayHit> castFrom(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                                         const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& direction,
                                         double length) {
  std::vector<simulation::Ray> rays(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    rays[i].origin = T_bin_grasp * points[i];
    rays[i].direction = T_bin_grasp.linear() * direction;
    rays[i].t_max = length;
  }
  return scene.caster().closestHits(rays);
}

double degrees(double radians) { return radians * 180.0 / M_PI; }

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return degrees(std::atan2(a.cross(b).norm(), a.dot(b)));
}

}  // namespace binpick::emptying::detail
