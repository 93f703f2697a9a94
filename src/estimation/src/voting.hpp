#pragma once
// The sparse voting scheme (section III-B): a share of the scene points act as references, each
// is paired with a share of the scene points within diam(M), matching pairs in the model table
// vote for (model point, alpha) local coordinates, and the top N_p local coordinates of each
// reference become pose candidates (eq. 2). No pose clustering. Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/core/cancellation.hpp"
#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/model.hpp"
#include "boundary.hpp"
#include "scene.hpp"

namespace binpick::estimation {

struct PoseCandidate {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  uint32_t votes = 0;
  uint32_t scene_reference = 0;  // index into PreparedScene
  uint32_t model_reference = 0;  // index into PreparedModel
};

// The outline's share of the votes (boundary.hpp): every scene boundary point within diam(M) of a
// reference is paired with it, and its surface-to-boundary matches vote into the same accumulator.
struct BoundaryVotes {
  const BoundaryModel& model;
  const BoundaryPoints& scene;
};

// Candidates ordered by reference point, then by votes (descending): the same for any thread count.
// Throws core::Cancelled once `cancel` is set (checked per reference point).
std::vector<PoseCandidate> vote(const PreparedModel& model, const PreparedScene& scene, const VotingParams& params,
                                const core::CancelFlag* cancel = nullptr, const BoundaryVotes* boundary = nullptr,
                                int threads = 0);

// The indices a fraction selects: a seeded shuffle's prefix, sorted.
std::vector<uint32_t> sampleIndices(std::size_t count, float fraction, uint64_t seed);

}  // namespace binpick::estimation
