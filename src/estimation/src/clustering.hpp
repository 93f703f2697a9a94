#pragma once
// Pose clustering of the original PPF method (section II-C), used by the Drost baseline: poses
// are grouped when both their translations and their rotations are close, a cluster scores the
// sum of its votes, and its pose is the vote-weighted average. Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "voting.hpp"

namespace binpick::estimation {

struct PoseCluster {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  uint32_t votes = 0;  // sum of the members' votes
  uint32_t members = 0;
};

// Clusters, best (most votes) first.
std::vector<PoseCluster> clusterPoses(const std::vector<PoseCandidate>& candidates, float diameter,
                                      const ClusteringParams& params);

}  // namespace binpick::estimation
