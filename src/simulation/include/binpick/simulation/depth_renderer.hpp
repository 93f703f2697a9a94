#pragma once
// A z-buffer rasteriser for an ideal pinhole depth sensor. The virtual cell renders with the ray
// caster (ray_caster.hpp, sensor_geometry.hpp); this independent implementation checks it in the
// tests, and defines RenderObject. The camera sits at the origin looking along +z, x right, y
// down. Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation {

struct PinholeCamera {
  int width = 1280;
  int height = 1024;
  double fx = 1600.0;  // pixels
  double fy = 1600.0;
  double cx = 639.5;
  double cy = 511.5;
};

struct RenderObject {
  const io::TriangleMesh* mesh = nullptr;
  Eigen::Isometry3d T_camera_object = Eigen::Isometry3d::Identity();
  int32_t id = 0;  // written to the instance image
};

struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth;       // z in the camera frame, +inf where nothing was hit
  std::vector<int32_t> instance;  // id of the object seen at each pixel, -1 where none
};

DepthImage renderDepth(const PinholeCamera& camera, const std::vector<RenderObject>& objects);

// Organized cloud (width x height, NaN where nothing was hit) from a depth image.
io::PointCloud depthToCloud(const PinholeCamera& camera, const DepthImage& image);

}  // namespace binpick::simulation
