#include "pile_view.hpp"

#include <cmath>
#include <limits>

namespace binpick::simulation::detail {
namespace {

io::PointCloud emptyOrganized(const SensorGeometry& geometry) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  io::PointCloud cloud;
  cloud.width = geometry.width;
  cloud.height = geometry.height;
  cloud.points.assign(static_cast<std::size_t>(geometry.width) * geometry.height, Eigen::Vector3f(nan, nan, nan));
  return cloud;
}

}  // namespace

std::vector<RenderObject> pileObjects(const io::TriangleMesh& part, const io::TriangleMesh& bin,
                                      const std::vector<Eigen::Isometry3d>& T_camera_object,
                                      const Eigen::Isometry3d& T_camera_bin) {
  std::vector<RenderObject> objects;
  for (const Eigen::Isometry3d& pose : T_camera_object) {
    objects.push_back({&part, pose, static_cast<int32_t>(objects.size())});
  }
  objects.push_back({&bin, T_camera_bin, kBinId});
  return objects;
}

io::PointCloud exactCloud(const SensorGeometry& geometry) {
  io::PointCloud cloud = emptyOrganized(geometry);
  cloud.normals = cloud.points;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (geometry.object_index[i] < 0) continue;
    cloud.points[i] = geometry.point[i];
    cloud.normals[i] = geometry.normal[i];
  }
  return cloud;
}

io::PointCloud measurableCloud(const SensorGeometry& geometry, double max_view_angle_deg) {
  const float min_cosine = static_cast<float>(std::cos(max_view_angle_deg * M_PI / 180.0));
  io::PointCloud cloud = emptyOrganized(geometry);
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (geometry.lit[i] && geometry.camera_cosine[i] >= min_cosine) {
      cloud.points[i] = geometry.point[i];
    }
  }
  return cloud;
}

AlbedoFunction pileAlbedo(const PileParams& params) {
  const float part = static_cast<float>(params.part_albedo);
  const float bin = static_cast<float>(params.bin_albedo);
  return [part, bin](int32_t id, const Eigen::Vector3f&) { return id == kBinId ? bin : part; };
}

}  // namespace binpick::simulation::detail
