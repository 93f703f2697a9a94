#include "pose_method.hpp"

namespace binpick::bench {

std::vector<Eigen::Vector3f> croppedPoints(const MethodInput& input) {
  std::vector<Eigen::Vector3f> kept;
  kept.reserve(input.cloud->points.size() / 4);
  for (const Eigen::Vector3f& p : input.cloud->points) {
    if (p.allFinite() && input.crop.contains(p)) kept.push_back(p);
  }
  return kept;
}

}  // namespace binpick::bench
