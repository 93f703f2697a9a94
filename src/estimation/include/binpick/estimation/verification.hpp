#pragma once
// Voxel-based pose verification (section III-C): every candidate's model points are moved into
// the scene and looked up in the voxel grid (eq. 3); the scene points they land near form
// SS(P_k), and the score counts those that still exist (eq. 4). Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/estimation/model.hpp"
#include "binpick/estimation/voting.hpp"
#include "binpick/estimation/voxel_grid.hpp"

namespace binpick::estimation {

struct VerificationParams {
  float voxel_size_ratio = 0.5f;        // L_voxel in subsampling steps (a model point fits when a scene
                                        // point lies within 1-2 voxels)
  float max_normal_angle_deg = 180.0f;  // a fit also needs the scene normal within this angle of
                                        // the moved model normal (180: off, as in the paper)
  int threads = 0;                      // 0: all hardware threads
  void validate() const;                // throws core::Error naming the field
};

struct VerifiedCandidate {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  uint32_t votes = 0;
  uint32_t score = 0;             // Score(P_k), eq. 4, with every scene point existing
  std::vector<uint32_t> support;  // SS(P_k): the scene point of every fitted model point
};

// SS(P) of one pose: the scene index of every fitted model point (duplicates kept: eq. 4 counts
// fitted model points).
std::vector<uint32_t> correspondingScenePoints(const PreparedModel& model, const Eigen::Isometry3f& pose,
                                               const SceneVoxelGrid& grid,
                                               const std::vector<Eigen::Vector3f>& scene_normals,
                                               float min_normal_cosine);

// Throws core::Cancelled once `cancel` is set (checked per candidate).
std::vector<VerifiedCandidate> verify(const std::vector<PoseCandidate>& candidates, const PreparedModel& model,
                                      const PreparedScene& scene, const SceneVoxelGrid& grid,
                                      const VerificationParams& params, const core::CancelFlag* cancel = nullptr);

// Eq. 4: how many entries of SS(P) still exist.
uint32_t existingCount(const std::vector<uint32_t>& support, const std::vector<uint8_t>& exist);

}  // namespace binpick::estimation
