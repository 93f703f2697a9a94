// renderDepth / depthToCloud: the public face of the rasteriser.
#include "binpick/simulation/depth_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "binpick/core/error.hpp"
#include "rasterizer.hpp"

namespace binpick::simulation {
namespace {

void requireValidCamera(const PinholeCamera& camera, const char* caller) {
  const bool ok = camera.width > 0 && camera.height > 0 && std::isfinite(camera.fx) && camera.fx > 0.0 &&
                  std::isfinite(camera.fy) && camera.fy > 0.0 && std::isfinite(camera.cx) && std::isfinite(camera.cy);
  if (!ok) {
    throw core::Error(std::string(caller) +
                      ": invalid PinholeCamera (width, height, fx, fy must be positive, cx, cy finite)");
  }
}

}  // namespace

DepthImage renderDepth(const PinholeCamera& camera, const std::vector<RenderObject>& objects) {
  requireValidCamera(camera, "renderDepth");
  const std::vector<detail::ScreenTriangle> triangles = detail::setupTriangles(camera, objects);
  DepthImage image;
  image.width = camera.width;
  image.height = camera.height;
  const std::size_t size = static_cast<std::size_t>(camera.width) * camera.height;
  image.depth.assign(size, std::numeric_limits<float>::infinity());
  image.instance.assign(size, -1);
  // Serial on purpose: a full 1280x1024 frame of a bin and 20 parts takes a few milliseconds, and
  // threads only cost time on a busy machine. The rasteriser draws into any window of the image,
  // so row bands could be split among threads without changing the result.
  const detail::PixelWindow whole_image{0, 0, camera.width, camera.height};
  detail::rasterize(camera, triangles, whole_image, image.depth.data(), image.instance.data());
  return image;
}

io::PointCloud depthToCloud(const PinholeCamera& camera, const DepthImage& image) {
  requireValidCamera(camera, "depthToCloud");
  const std::size_t size = static_cast<std::size_t>(image.width) * image.height;
  if (image.width != camera.width || image.height != camera.height || image.depth.size() != size) {
    throw core::Error("depthToCloud: the depth image does not match the camera size");
  }
  io::PointCloud cloud;
  cloud.width = image.width;
  cloud.height = image.height;
  cloud.points.resize(size);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < image.height; ++v) {
    const double ray_y = (v - camera.cy) / camera.fy;
    for (int u = 0; u < image.width; ++u) {
      const std::size_t pixel = static_cast<std::size_t>(v) * image.width + u;
      const float z = image.depth[pixel];
      if (!std::isfinite(z)) {
        cloud.points[pixel] = Eigen::Vector3f(nan, nan, nan);
        continue;
      }
      const double ray_x = (u - camera.cx) / camera.fx;
      // z is copied, not multiplied, so that point.z() == depth exactly.
      cloud.points[pixel] = Eigen::Vector3f(static_cast<float>(z * ray_x), static_cast<float>(z * ray_y), z);
    }
  }
  return cloud;
}

}  // namespace binpick::simulation
