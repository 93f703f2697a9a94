#pragma once
// The sparse voting scheme (section III-B): a share of the scene points act as references, each
// is paired with a share of the scene points within diam(M), matching pairs in the model table
// vote for (model point, alpha) local coordinates, and the top N_p local coordinates of each
// reference become pose candidates (eq. 2). No pose clustering. Thread-safe (no shared state).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/core/cancellation.hpp"
#include "binpick/estimation/boundary.hpp"
#include "binpick/estimation/model.hpp"
#include "binpick/estimation/scene.hpp"

namespace binpick::estimation {

struct VotingParams {
  float reference_fraction = 0.1f;  // share of scene points used as references (Table I: 10%)
  float referred_fraction = 0.2f;   // share of scene points paired with them (Table I: 20%)
  int poses_per_reference = 5;      // N_p: top local coordinates kept per reference
  float min_relative_votes = 0.0f;  // keep a local coordinate only with >= this share of the
                                    // reference's best vote count (Drost keeps near-peaks)
  uint64_t seed = 1;                // which points are references and referred points
  int threads = 0;                  // 0: all hardware threads
  void validate() const;            // throws core::Error naming the field
};

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
                                const core::CancelFlag* cancel = nullptr, const BoundaryVotes* boundary = nullptr);

// The indices a fraction selects: a seeded shuffle's prefix, sorted (exposed for tests).
std::vector<uint32_t> sampleIndices(std::size_t count, float fraction, uint64_t seed);

}  // namespace binpick::estimation
