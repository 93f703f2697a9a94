// Multiple selection (section III-D, Algorithm 1) against a naive re-scoring of every candidate.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <random>

#include "estimation_test_support.hpp"
#include "selection.hpp"

namespace binpick::estimation {
namespace {

using Pick = MultipleSelection::Pick;

// Random supports over a scene of `scene_points`; duplicates allowed (eq. 4 counts model points).
std::vector<VerifiedCandidate> randomCandidates(std::size_t count, std::size_t scene_points, int min_support,
                                                int max_support, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> size(min_support, max_support);
  std::uniform_int_distribution<uint32_t> point(0, static_cast<uint32_t>(scene_points - 1));
  std::vector<VerifiedCandidate> candidates(count);
  for (auto& c : candidates) {
    const int n = size(rng);
    for (int k = 0; k < n; ++k) c.support.push_back(point(rng));
    c.score = static_cast<uint32_t>(c.support.size());
  }
  return candidates;
}

// The definition: every round, re-score every remaining candidate and take the best (ties: the
// lower index); its support stops existing.
std::vector<Pick> naiveSelection(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points,
                                 std::size_t* evaluations, const std::vector<uint32_t>& penalties = {}) {
  std::vector<uint8_t> exist(scene_points, 1);
  std::vector<bool> taken(candidates.size(), false);
  std::vector<Pick> picks;
  *evaluations = 0;
  for (std::size_t round = 0; round < candidates.size(); ++round) {
    int best = -1;
    uint32_t best_score = 0;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (taken[c]) continue;
      uint32_t s = existingCount(candidates[c].support, exist);
      if (!penalties.empty()) s -= std::min(s, penalties[c]);
      ++*evaluations;
      if (best < 0 || s > best_score) {
        best = static_cast<int>(c);
        best_score = s;
      }
    }
    taken[best] = true;
    picks.push_back({static_cast<uint32_t>(best), best_score});
    for (uint32_t s : candidates[best].support) exist[s] = 0;
  }
  return picks;
}

std::vector<Pick> lazySelection(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points,
                                std::size_t* refreshes) {
  MultipleSelection selection(candidates, scene_points);
  std::vector<Pick> picks;
  while (const auto pick = selection.next()) {
    picks.push_back(*pick);
    selection.removeExplained(candidates[pick->candidate].support);
  }
  *refreshes = selection.refreshCount();
  return picks;
}

void expectSameSequence(const std::vector<Pick>& lazy, const std::vector<Pick>& naive) {
  ASSERT_EQ(lazy.size(), naive.size());
  for (std::size_t k = 0; k < naive.size(); ++k) {
    EXPECT_EQ(lazy[k].candidate, naive[k].candidate) << "pick " << k;
    EXPECT_EQ(lazy[k].score, naive[k].score) << "pick " << k;
    if (lazy[k].candidate != naive[k].candidate) return;  // the rest differs as a consequence
  }
}

TEST(MultipleSelection, SameSequenceAsNaiveRescoring) {
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    SCOPED_TRACE(seed);
    const auto candidates = randomCandidates(60, 200, 0, 60, seed);
    std::size_t naive_evaluations = 0, refreshes = 0;
    const auto naive = naiveSelection(candidates, 200, &naive_evaluations);
    expectSameSequence(lazySelection(candidates, 200, &refreshes), naive);
  }
}

TEST(MultipleSelection, TiesGoToTheLowerIndex) {
  // Few distinct scores and overlapping supports: ties at every round.
  for (uint64_t seed = 100; seed < 130; ++seed) {
    SCOPED_TRACE(seed);
    const auto candidates = randomCandidates(80, 40, 2, 4, seed);
    std::size_t naive_evaluations = 0, refreshes = 0;
    const auto naive = naiveSelection(candidates, 40, &naive_evaluations);
    expectSameSequence(lazySelection(candidates, 40, &refreshes), naive);
  }
  // Identical candidates: picked in index order, the first with the full score, then zero.
  std::vector<VerifiedCandidate> same(5);
  for (auto& c : same) {
    c.support = {1, 2, 3};
    c.score = 3;
  }
  std::size_t refreshes = 0;
  const auto picks = lazySelection(same, 10, &refreshes);
  ASSERT_EQ(picks.size(), 5u);
  for (uint32_t k = 0; k < 5; ++k) {
    EXPECT_EQ(picks[k].candidate, k);
    EXPECT_EQ(picks[k].score, k == 0 ? 3u : 0u);
  }
}

TEST(MultipleSelection, LazyRefreshEvaluatesFewerScoresThanNaive) {
  // Many candidates, as after voting: most are never refreshed more than a few times.
  const auto candidates = randomCandidates(2000, 200, 0, 40, 7);
  std::size_t naive_evaluations = 0, refreshes = 0;
  const auto naive = naiveSelection(candidates, 200, &naive_evaluations);
  const auto lazy = lazySelection(candidates, 200, &refreshes);
  expectSameSequence(lazy, naive);
  EXPECT_LT(refreshes, naive_evaluations);
  EXPECT_LT(refreshes * 10, naive_evaluations) << "refreshes " << refreshes << ", naive " << naive_evaluations;

  // The first pick of a fresh selection is the top score; refreshing only until nothing can beat
  // it costs few evaluations.
  MultipleSelection selection(candidates, 200);
  const auto first = selection.next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->candidate, naive[0].candidate);
  EXPECT_LT(selection.refreshCount(), candidates.size() / 10);
}

// The scene-consistent verification's penalty: the same sequence as re-scoring every candidate
// with eq. 4 less its penalty, each penalty computed at most once and only for the candidates
// Algorithm 1 refreshes.
TEST(MultipleSelection, APenaltyTakenOffAtTheFirstRefreshGivesTheNaiveSequence) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    const auto candidates = randomCandidates(300, 200, 0, 60, seed);
    std::mt19937_64 rng(seed + 1000);
    std::uniform_int_distribution<uint32_t> cost(0, 40);
    std::vector<uint32_t> penalties(candidates.size());
    for (uint32_t& p : penalties) p = cost(rng);
    std::size_t naive_evaluations = 0;
    const auto naive = naiveSelection(candidates, 200, &naive_evaluations, penalties);

    std::vector<int> computed(candidates.size(), 0);
    MultipleSelection selection(candidates, 200, [&](uint32_t c) {
      ++computed[c];
      return penalties[c];
    });
    std::vector<Pick> lazy;
    while (const auto pick = selection.next()) {
      lazy.push_back(*pick);
      selection.removeExplained(candidates[pick->candidate].support);
    }
    expectSameSequence(lazy, naive);
    for (int n : computed) EXPECT_LE(n, 1);
  }
  // One pick from many candidates computes few penalties, on two threads too.
  const auto candidates = randomCandidates(2000, 200, 0, 40, 7);
  std::atomic<std::size_t> computed{0};
  MultipleSelection selection(
      candidates, 200,
      [&](uint32_t) {
        ++computed;
        return 5u;
      },
      2);
  ASSERT_TRUE(selection.next().has_value());
  EXPECT_LT(computed.load(), candidates.size() / 5);
}

// A minimum score ends the selection where the naive one first picks below it, without the
// penalties of candidates that can no longer reach it.
TEST(MultipleSelection, AMinimumScoreStopsWhereTheNaiveSequenceFallsBelowIt) {
  constexpr uint32_t kMinScore = 20;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    const auto candidates = randomCandidates(300, 200, 0, 60, seed);
    std::vector<uint32_t> penalties(candidates.size());
    for (std::size_t c = 0; c < penalties.size(); ++c) penalties[c] = static_cast<uint32_t>(c % 7);
    std::size_t naive_evaluations = 0;
    std::vector<Pick> naive = naiveSelection(candidates, 200, &naive_evaluations, penalties);
    naive.erase(std::find_if(naive.begin(), naive.end(), [](const Pick& p) { return p.score < kMinScore; }),
                naive.end());

    std::vector<int> computed(candidates.size(), 0);
    const auto penalty = [&](uint32_t c) {
      ++computed[c];
      return penalties[c];
    };
    MultipleSelection selection(candidates, 200, penalty, 1, kMinScore);
    std::vector<Pick> lazy;
    while (const auto pick = selection.next()) {
      lazy.push_back(*pick);
      selection.removeExplained(candidates[pick->candidate].support);
    }
    expectSameSequence(lazy, naive);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (candidates[c].score < kMinScore) {
        EXPECT_EQ(computed[c], 0) << "candidate " << c;
      }
    }
    EXPECT_FALSE(selection.next().has_value());
  }
}

TEST(MultipleSelection, ExistFlagsAndEmptyInput) {
  const std::vector<VerifiedCandidate> none;
  MultipleSelection empty(none, 10);
  EXPECT_FALSE(empty.next().has_value());
  EXPECT_EQ(empty.refreshCount(), 0u);

  std::vector<VerifiedCandidate> candidates(2);
  candidates[0].support = {0, 1, 2, 3};
  candidates[0].score = 4;
  candidates[1].support = {2, 3, 4};
  candidates[1].score = 3;
  MultipleSelection selection(candidates, 6);
  EXPECT_EQ(selection.exist(), (std::vector<uint8_t>{1, 1, 1, 1, 1, 1}));
  auto pick = selection.next();
  ASSERT_TRUE(pick);
  EXPECT_EQ(pick->candidate, 0u);
  EXPECT_EQ(pick->score, 4u);
  selection.removeExplained(candidates[0].support);
  EXPECT_EQ(selection.exist(), (std::vector<uint8_t>{0, 0, 0, 0, 1, 1}));
  pick = selection.next();
  ASSERT_TRUE(pick);
  EXPECT_EQ(pick->candidate, 1u);
  EXPECT_EQ(pick->score, 1u) << "only scene point 4 still exists";
  EXPECT_FALSE(selection.next().has_value());
}

}  // namespace
}  // namespace binpick::estimation
