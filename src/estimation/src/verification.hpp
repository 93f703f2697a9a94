#pragma once
// Voxel-based pose verification (section III-C): every candidate's model points are moved into
// the scene and looked up in the voxel grid (eq. 3); the scene points they land near form
// SS(P_k), and the score counts those that still exist (eq. 4). Thread-safe (no shared state).
//
// Deviation: scene-consistent verification. A pose also pays for what the camera would have seen
// were it right: every model point lying in front of the measured surface along its line of sight
// (free space the sensor saw through) costs `free_space_penalty` score points, taken off when
// Algorithm 1 first refreshes the candidate (freeSpacePenalty, MultipleSelection). Eq. 4 counts only
// what a pose explains, so a part turned over that shows the same single face (a flange with its
// hub put on the hidden side, an L-bracket upside down) scores as high as the truth; its hidden
// half, now towards the camera, floats in front of the pile and is caught here. A point inside a
// part seen by the camera is seen through the part's front too, so one test covers both.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/model.hpp"
#include "line_of_sight.hpp"
#include "voting.hpp"
#include "voxel_grid.hpp"

namespace binpick::estimation {

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
                                      const VerificationParams& params, const core::CancelFlag* cancel = nullptr,
                                      int threads = 0);

// How many of the model points at `pose` that the camera would measure (facing it, not grazing)
// lie more than `tolerance` in front of the measured surface; only `indices` when given, else all.
uint32_t seenThroughCount(const PreparedModel& model, const Eigen::Isometry3f& pose, const LineOfSightMap& map,
                          float tolerance, const std::vector<uint32_t>* indices = nullptr);

// The score a pose pays for what the camera saw through (free_space_penalty x seen-through model
// points at free_space_tolerance_ratio); 0 when the penalty is off or the scene has no map.
uint32_t freeSpacePenalty(const PreparedModel& model, const PreparedScene& scene, const Eigen::Isometry3f& pose,
                          const VerificationParams& params);

// Eq. 4: how many entries of SS(P) still exist.
uint32_t existingCount(const std::vector<uint32_t>& support, const std::vector<uint8_t>& exist);

}  // namespace binpick::estimation
