#include "clustering.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "binpick/core/error.hpp"

namespace binpick::estimation {
namespace {

struct Accumulating {
  Eigen::Isometry3f seed;  // the first (highest-voted) member decides membership
  Eigen::Vector3d translation_sum = Eigen::Vector3d::Zero();
  Eigen::Vector4d quaternion_sum = Eigen::Vector4d::Zero();
  uint32_t votes = 0;
  uint32_t members = 0;

  void add(const PoseCandidate& c) {
    const double w = c.votes;
    translation_sum += w * c.T_camera_model.translation().cast<double>();
    Eigen::Quaterniond q(c.T_camera_model.linear().cast<double>());
    const Eigen::Quaterniond reference(seed.linear().cast<double>());
    if (q.coeffs().dot(reference.coeffs()) < 0.0) q.coeffs() *= -1.0;  // q and -q are one rotation
    quaternion_sum += w * q.coeffs();
    votes += c.votes;
    ++members;
  }
  PoseCluster result() const {
    PoseCluster cluster;
    cluster.votes = votes;
    cluster.members = members;
    const double total = std::max<double>(votes, 1.0);
    Eigen::Quaterniond mean;
    mean.coeffs() = quaternion_sum;
    cluster.T_camera_model.linear() = mean.normalized().toRotationMatrix().cast<float>();
    cluster.T_camera_model.translation() = (translation_sum / total).cast<float>();
    return cluster;
  }
};

float rotationAngle(const Eigen::Matrix3f& a, const Eigen::Matrix3f& b) {
  const float cosine = std::clamp(((a.transpose() * b).trace() - 1.0f) * 0.5f, -1.0f, 1.0f);
  return std::acos(cosine);
}

}  // namespace

void ClusteringParams::validate() const {
  const char* owner = "detection.clustering";
  core::requireField(max_translation_ratio > 0.0f && max_translation_ratio <= 1.0f, owner, "max_translation_ratio",
                     "in (0, 1]", max_translation_ratio);
  core::requireField(max_rotation_deg > 0.0f && max_rotation_deg <= 180.0f, owner, "max_rotation_deg", "in (0, 180]",
                     max_rotation_deg);
}

std::vector<PoseCluster> clusterPoses(const std::vector<PoseCandidate>& candidates, float diameter,
                                      const ClusteringParams& params) {
  params.validate();
  std::vector<uint32_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return candidates[a].votes > candidates[b].votes; });
  const float max_translation = params.max_translation_ratio * diameter;
  const float max_rotation = params.max_rotation_deg * static_cast<float>(M_PI / 180.0);
  std::vector<Accumulating> clusters;
  for (uint32_t index : order) {
    const PoseCandidate& c = candidates[index];
    auto home = std::find_if(clusters.begin(), clusters.end(), [&](const Accumulating& cluster) {
      return (cluster.seed.translation() - c.T_camera_model.translation()).norm() <= max_translation &&
             rotationAngle(cluster.seed.linear(), c.T_camera_model.linear()) <= max_rotation;
    });
    if (home == clusters.end()) {
      clusters.push_back(Accumulating{c.T_camera_model});
      home = clusters.end() - 1;
    }
    home->add(c);
  }
  std::vector<PoseCluster> result;
  result.reserve(clusters.size());
  for (const auto& cluster : clusters) result.push_back(cluster.result());
  std::stable_sort(result.begin(), result.end(),
                   [](const PoseCluster& a, const PoseCluster& b) { return a.votes > b.votes; });
  return result;
}

}  // namespace binpick::estimation
