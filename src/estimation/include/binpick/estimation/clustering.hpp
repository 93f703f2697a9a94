#pragma once
// Pose clustering of the original PPF method (section II-C), used by the Drost baseline: poses
// are grouped when both their translations and their rotations are close, a cluster scores the
// sum of its votes, and its pose is the vote-weighted average. Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <vector>

#include "binpick/estimation/voting.hpp"

namespace binpick::estimation {

struct ClusteringParams {
  float max_translation_ratio = 0.1f;  // in diam(M): translations closer than this may join
  float max_rotation_deg = 12.0f;      // and rotations closer than this (both must hold)
  void validate() const;               // throws core::Error naming the field
};

struct PoseCluster {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  uint32_t votes = 0;  // sum of the members' votes
  uint32_t members = 0;
};

// Clusters, best (most votes) first.
std::vector<PoseCluster> clusterPoses(const std::vector<PoseCandidate>& candidates, float diameter,
                                      const ClusteringParams& params);

}  // namespace binpick::estimation
