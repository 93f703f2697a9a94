#include "verification.hpp"

#include <cmath>

#include "binpick/core/error.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {

void VerificationParams::validate() const {
  const char* owner = "detection.verification";
  core::requireField(voxel_size_ratio >= 0.1f && voxel_size_ratio <= 5.0f, owner, "voxel_size_ratio", "in [0.1, 5]",
                     voxel_size_ratio);
  core::requireField(max_normal_angle_deg > 0.0f && max_normal_angle_deg <= 180.0f, owner, "max_normal_angle_deg",
                     "in (0, 180]", max_normal_angle_deg);
  core::requireField(free_space_tolerance_ratio > 0.0f && free_space_tolerance_ratio <= 100.0f, owner,
                     "free_space_tolerance_ratio", "in (0, 100]", free_space_tolerance_ratio);
  core::requireField(free_space_penalty >= 0.0f && free_space_penalty <= 100.0f, owner, "free_space_penalty",
                     "in [0, 100]", free_space_penalty);
  core::requireField(refined_tolerance_ratio > 0.0f && refined_tolerance_ratio <= 100.0f, owner,
                     "refined_tolerance_ratio", "in (0, 100]", refined_tolerance_ratio);
  core::requireField(max_refined_seen_through >= 0.0f && max_refined_seen_through <= 1.0f, owner,
                     "max_refined_seen_through", "in [0, 1]", max_refined_seen_through);
}

std::vector<uint32_t> correspondingScenePoints(const PreparedModel& model, const Eigen::Isometry3f& pose,
                                               const SceneVoxelGrid& grid,
                                               const std::vector<Eigen::Vector3f>& scene_normals,
                                               float min_normal_cosine) {
  std::vector<uint32_t> support;
  support.reserve(model.size() / 2);
  const bool check_normals = min_normal_cosine > -1.0f;
  const Eigen::Affine3f to_voxels = grid.voxelMapOf(pose);
  for (std::size_t k = 0; k < model.size(); ++k) {
    const int32_t s = grid.atVoxelCoordinates(to_voxels * model.points[k]);
    if (s == SceneVoxelGrid::kEmpty) continue;
    if (check_normals && (pose.linear() * model.normals[k]).dot(scene_normals[s]) < min_normal_cosine) continue;
    support.push_back(static_cast<uint32_t>(s));
  }
  return support;
}

uint32_t seenThroughCount(const PreparedModel& model, const Eigen::Isometry3f& pose, const LineOfSightMap& map,
                          float tolerance, const std::vector<uint32_t>* indices) {
  if (map.empty()) return 0;
  const auto seen_through = [&](std::size_t k) {
    return map.seenThrough(pose * model.points[k], pose.linear() * model.normals[k], tolerance) ? 1u : 0u;
  };
  uint32_t count = 0;
  if (indices) {
    for (uint32_t k : *indices) count += seen_through(k);
  } else {
    for (std::size_t k = 0; k < model.size(); ++k) count += seen_through(k);
  }
  return count;
}

uint32_t freeSpacePenalty(const PreparedModel& model, const PreparedScene& scene, const Eigen::Isometry3f& pose,
                          const VerificationParams& params) {
  if (!(params.free_space_penalty > 0.0f)) return 0;
  const uint32_t seen_through =
      seenThroughCount(model, pose, scene.line_of_sight, params.free_space_tolerance_ratio * model.step);
  return static_cast<uint32_t>(std::lround(params.free_space_penalty * static_cast<float>(seen_through)));
}

std::vector<VerifiedCandidate> verify(const std::vector<PoseCandidate>& candidates, const PreparedModel& model,
                                      const PreparedScene& scene, const SceneVoxelGrid& grid,
                                      const VerificationParams& params, const core::CancelFlag* cancel, int threads) {
  params.validate();
  const float min_cosine = params.max_normal_angle_deg >= 180.0f
                               ? -2.0f
                               : std::cos(params.max_normal_angle_deg * static_cast<float>(M_PI / 180.0));
  std::vector<VerifiedCandidate> verified(candidates.size());
#pragma omp parallel for num_threads(core::resolveThreadCount(threads)) schedule(dynamic, 16)
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (core::isCancelled(cancel)) continue;  // the rest is skipped; the throw comes after the loop
    VerifiedCandidate& v = verified[c];
    v.T_camera_model = candidates[c].T_camera_model;
    v.votes = candidates[c].votes;
    v.support = correspondingScenePoints(model, v.T_camera_model, grid, scene.normals, min_cosine);
    v.score = static_cast<uint32_t>(v.support.size());
  }
  core::throwIfCancelled(cancel, "during verification");
  return verified;
}

uint32_t existingCount(const std::vector<uint32_t>& support, const std::vector<uint8_t>& exist) {
  uint32_t count = 0;
  for (uint32_t s : support) count += exist[s];
  return count;
}

}  // namespace binpick::estimation
