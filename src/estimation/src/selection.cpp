#include "selection.hpp"

#include <algorithm>

#include "binpick/core/error.hpp"

namespace binpick::estimation {

void SelectionParams::validate() const {
  const char* owner = "detection.selection";
  core::requireField(max_objects >= 1 && max_objects <= 10000, owner, "max_objects", "in [1, 10000]", max_objects);
  core::requireField(min_score_fraction >= 0.0f && min_score_fraction <= 1.0f, owner, "min_score_fraction", "in [0, 1]",
                     min_score_fraction);
  core::requireField(min_coverage >= 0.0f && min_coverage <= 1.0f, owner, "min_coverage", "in [0, 1]", min_coverage);
  core::requireField(min_centre_distance_ratio >= 0.0f && min_centre_distance_ratio <= 10.0f, owner,
                     "min_centre_distance_ratio", "in [0, 10]", min_centre_distance_ratio);
  core::requireField(sure_twin_margin >= 0.0f && sure_twin_margin <= 1.0f, owner, "sure_twin_margin", "in [0, 1]",
                     sure_twin_margin);
  core::requireField(sure_coverage >= 0.0f && sure_coverage <= 1.0f, owner, "sure_coverage", "in [0, 1]",
                     sure_coverage);
}

MultipleSelection::MultipleSelection(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points,
                                     Penalty penalty, int threads, uint32_t min_score)
    : candidates_(candidates),
      penalty_(std::move(penalty)),
      threads_(std::max(1, threads)),
      min_score_(min_score),
      known_penalty_(penalty_ ? candidates.size() : 0, -1),
      exist_(scene_points, 1) {
  ranked_.reserve(candidates.size());
  for (uint32_t i = 0; i < candidates.size(); ++i) ranked_.emplace_back(candidates[i].score, i);
  unsorted_ = ranked_.size();
}

namespace {

// Higher score first; ties: the lower index. A strict total order: the ranking is unique.
bool ranksBefore(const std::pair<uint32_t, uint32_t>& a, const std::pair<uint32_t, uint32_t>& b) {
  return a.first != b.first ? a.first > b.first : a.second < b.second;
}

}  // namespace

std::optional<MultipleSelection::Pick> MultipleSelection::next() {
  if (ranked_.empty()) return std::nullopt;
  // "Rank P based on their old scores": a score only falls when points stop existing, so the
  // last known score is an upper bound of the new one. Only the head refreshed by the last call
  // is out of order: it is sorted and merged with the rest (a full sort of thousands of candidates
  // at every pick took a tenth of the selection).
  const auto refreshed_end = ranked_.begin() + static_cast<std::ptrdiff_t>(unsorted_);
  std::sort(ranked_.begin(), refreshed_end, ranksBefore);
  std::inplace_merge(ranked_.begin(), refreshed_end, ranked_.end(), ranksBefore);
  std::size_t best = 0;
  std::size_t refreshed = 0;
  // Nothing from the first candidate whose bound is below min_score on can be picked.
  for (std::size_t i = 0; i < ranked_.size() && ranked_[i].first >= min_score_; ++i) {
    // Eq. 4 less the candidate's penalty, which no removal changes: the last known score stays an
    // upper bound. Below min_score without it, eq. 4 alone is the bound: the penalty never counts.
    const uint32_t existing = existingCount(candidates_[ranked_[i].second].support, exist_);
    ranked_[i].first = existing < min_score_ ? existing : existing - std::min(existing, penaltyAt(i));
    ++refreshes_;
    refreshed = i + 1;
    if (ranksBefore(ranked_[i], ranked_[best])) best = i;
    if (i + 1 == ranked_.size()) break;
    // Max_New_Score >= Score_Old(P_{i+1}): nothing further down can win (ties go to the lower
    // index, as a full re-verification would break them).
    if (ranksBefore(ranked_[best], ranked_[i + 1])) break;
  }
  // Nothing refreshed: the first bound (best's) was below min_score already.
  if (ranked_[best].first < min_score_) {
    unsorted_ = refreshed;
    return std::nullopt;
  }
  const Pick pick{ranked_[best].second, ranked_[best].first};
  ranked_.erase(ranked_.begin() + static_cast<std::ptrdiff_t>(best));
  unsorted_ = refreshed - 1;  // the pick came out of the refreshed head
  return pick;
}

uint32_t MultipleSelection::penaltyAt(std::size_t rank) {
  if (!penalty_) return 0;
  const uint32_t candidate = ranked_[rank].second;
  if (known_penalty_[candidate] < 0) {
    // The candidates ranked next are the likeliest to be refreshed next: their penalties are
    // computed now, side by side on the threads.
    std::vector<uint32_t> batch;
    for (std::size_t r = rank; r < ranked_.size() && ranked_[r].first >= min_score_ && batch.size() < kPenaltyBatch;
         ++r) {
      if (known_penalty_[ranked_[r].second] < 0) batch.push_back(ranked_[r].second);
    }
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1)
    for (std::size_t b = 0; b < batch.size(); ++b) known_penalty_[batch[b]] = penalty_(batch[b]);
  }
  return static_cast<uint32_t>(known_penalty_[candidate]);
}

void MultipleSelection::removeExplained(const std::vector<uint32_t>& scene_points) {
  for (uint32_t s : scene_points) exist_[s] = 0;
}

}  // namespace binpick::estimation
