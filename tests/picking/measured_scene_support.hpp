#pragma once
// Measured clouds for the tool's collision tests, written straight in the base frame: planes,
// columns and slabs sampled every millimetre (finer than the scene's 3 mm thinning).
#include <Eigen/Geometry>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/tool_collision.hpp"

namespace binpick::picking::test {

constexpr double kSampleStep = 0.001;

struct CloudBuilder {
  std::vector<Eigen::Vector3f> points;

  // The horizontal rectangle [x0, x1] x [y0, y1] at height z.
  CloudBuilder& slab(double x0, double x1, double y0, double y1, double z) {
    for (double x = x0; x <= x1 + 1e-9; x += kSampleStep) {
      for (double y = y0; y <= y1 + 1e-9; y += kSampleStep) points.emplace_back(x, y, z);
    }
    return *this;
  }
  // A vertical line of points at (x, y) from z0 up to z1.
  CloudBuilder& column(double x, double y, double z0, double z1) {
    for (double z = z0; z <= z1 + 1e-9; z += kSampleStep) points.emplace_back(x, y, z);
    return *this;
  }
  CloudBuilder& point(double x, double y, double z) {
    points.emplace_back(x, y, z);
    return *this;
  }
  // An unorganized cloud already in the base frame (T_base_camera = identity).
  MeasuredScene scene() const {
    io::PointCloud cloud;
    cloud.points = points;
    return MeasuredScene(cloud, Eigen::Isometry3d::Identity());
  }
};

}  // namespace binpick::picking::test
