#pragma once
// Multiple selection (section III-D, Algorithm 1): scene points explained by an accepted pose stop
// existing, and the next pose is found by refreshing candidates' scores (eq. 4 over the stored
// SS(P_k)) in the order of their last known scores, stopping as soon as no unrefreshed candidate
// can beat the best refreshed one. Not thread-safe: one selection per detection.
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "verification.hpp"

namespace binpick::estimation {

class MultipleSelection {
 public:
  struct Pick {
    uint32_t candidate = 0;  // index into the candidates
    uint32_t score = 0;      // Score_New at the time of the pick
  };

  // A fixed cost subtracted from a candidate's eq. 4 score (the free-space penalty of the
  // scene-consistent verification), computed the first time the candidate is refreshed: most
  // candidates never are, and an upper bound stays one when the cost is taken off.
  using Penalty = std::function<uint32_t(uint32_t candidate)>;

  // `candidates` must outlive the selection. Without a penalty: eq. 4 alone, as in the paper.
  // `penalty` must be thread-safe: it runs on up to `threads` threads. No pick scores below
  // `min_score`: candidates that cannot reach it are neither refreshed nor penalised.
  MultipleSelection(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points,
                    Penalty penalty = nullptr, int threads = 1, uint32_t min_score = 0);

  // The remaining candidate with the highest Score_New under the current Exist flags (ties: the
  // lower index), taken out of the running; nothing when no candidate is left with at least
  // min_score.
  std::optional<Pick> next();
  // Algorithm 1 lines 2-6: these scene points stop existing.
  void removeExplained(const std::vector<uint32_t>& scene_points);

  const std::vector<uint8_t>& exist() const { return exist_; }
  std::size_t refreshCount() const { return refreshes_; }  // how many eq. 4 evaluations ran

 private:
  static constexpr std::size_t kPenaltyBatch = 32;
  uint32_t penaltyAt(std::size_t rank);  // of the candidate at ranked_[rank]

  const std::vector<VerifiedCandidate>& candidates_;
  Penalty penalty_;
  int threads_;
  uint32_t min_score_;
  std::vector<int64_t> known_penalty_;  // -1 until computed
  std::vector<uint8_t> exist_;
  std::vector<std::pair<uint32_t, uint32_t>> ranked_;  // (known upper bound of the score, index)
  std::size_t unsorted_ = 0;                           // ranked_'s head refreshed since it was sorted
  std::size_t refreshes_ = 0;
};

}  // namespace binpick::estimation
