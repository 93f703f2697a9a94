// Sparse voting (section III-B) against a brute-force vote written out in the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <unordered_map>

#include "estimation_test_support.hpp"
#include "voting.hpp"

namespace binpick::estimation {
namespace {

using testing::randomPose;
using testing::rotationErrorDeg;
using testing::smallModel;
using testing::translationError;

// The model's own points seen at pose T: every scene point has an exact model counterpart.
PreparedScene transformedModel(const PreparedModel& model, const Eigen::Isometry3f& T) {
  PreparedScene scene;
  for (std::size_t k = 0; k < model.size(); ++k) {
    scene.points.push_back(T * model.points[k]);
    scene.normals.push_back((T.linear() * model.normals[k]).normalized());
    scene.source_index.push_back(static_cast<uint32_t>(k));
  }
  scene.valid_input_points = scene.size();
  return scene;
}

struct Cell {
  uint32_t votes;
  uint32_t model_point;
  int alpha_bin;
};

// For each scene reference: the local coordinates ordered by votes (descending), ties by
// accumulator index (model point * alpha bins + alpha bin) ascending.
std::vector<std::vector<Cell>> bruteForceVote(const PreparedModel& model, const PreparedScene& scene,
                                              std::size_t keep) {
  const PpfQuantizer q = model.quantizer();
  // Every ordered model pair's key, computed directly (not through the library's table).
  std::unordered_map<int64_t, std::vector<std::pair<uint32_t, float>>> model_pairs;
  for (uint32_t a = 0; a < model.size(); ++a) {
    const Eigen::Isometry3f T_m = referenceFrame(model.points[a], model.normals[a]);
    for (uint32_t b = 0; b < model.size(); ++b) {
      if (a == b) continue;
      const int64_t key = q.pairKey(model.points[a], model.normals[a], model.points[b], model.normals[b]);
      if (key >= 0) model_pairs[key].emplace_back(a, planarAngle(T_m * model.points[b]));
    }
  }
  const int bins = q.alphaBinCount();
  std::vector<std::vector<Cell>> result(scene.size());
  std::vector<uint32_t> accumulator(model.size() * static_cast<std::size_t>(bins));
  for (std::size_t r = 0; r < scene.size(); ++r) {
    std::fill(accumulator.begin(), accumulator.end(), 0u);
    const Eigen::Isometry3f T_s = referenceFrame(scene.points[r], scene.normals[r]);
    for (std::size_t j = 0; j < scene.size(); ++j) {
      if (j == r || (scene.points[j] - scene.points[r]).squaredNorm() > model.diameter * model.diameter) continue;
      const int64_t key = q.pairKey(scene.points[r], scene.normals[r], scene.points[j], scene.normals[j]);
      const auto it = model_pairs.find(key);
      if (key < 0 || it == model_pairs.end()) continue;
      const float alpha_s = planarAngle(T_s * scene.points[j]);
      for (const auto& [m, alpha_m] : it->second) {
        // alphaBin(alpha_s - alpha_m), through the same float expression as the voting: the two
        // agree except for a difference within an ulp of a bin edge (test_ppf.cpp), which would
        // make an exact vote count comparison fragile.
        ++accumulator[static_cast<std::size_t>(m) * bins + q.alphaBinOfDifference(alpha_s, alpha_m)];
      }
    }
    std::vector<uint32_t> cells(accumulator.size());
    std::iota(cells.begin(), cells.end(), 0u);
    std::stable_sort(cells.begin(), cells.end(),
                     [&](uint32_t a, uint32_t b) { return accumulator[a] > accumulator[b]; });
    for (std::size_t k = 0; k < keep && k < cells.size() && accumulator[cells[k]] > 0; ++k) {
      result[r].push_back({accumulator[cells[k]], cells[k] / static_cast<uint32_t>(bins),
                           static_cast<int>(cells[k] % static_cast<uint32_t>(bins))});
    }
  }
  return result;
}

VotingParams allPairs(int poses_per_reference) {
  VotingParams p;
  p.reference_fraction = 1.0f;
  p.referred_fraction = 1.0f;
  p.poses_per_reference = poses_per_reference;
  return p;
}

void expectSameAsBruteForce(const PreparedModel& model, const PreparedScene& scene,
                            const std::vector<PoseCandidate>& candidates,
                            const std::vector<std::vector<Cell>>& expected) {
  const PpfQuantizer q = model.quantizer();
  std::size_t next = 0;
  for (std::size_t r = 0; r < scene.size(); ++r) {
    const Eigen::Isometry3f T_s = referenceFrame(scene.points[r], scene.normals[r]);
    for (const Cell& cell : expected[r]) {
      ASSERT_LT(next, candidates.size()) << "missing candidates from reference " << r;
      const PoseCandidate& c = candidates[next++];
      SCOPED_TRACE(::testing::Message() << "reference " << r);
      EXPECT_EQ(c.scene_reference, r);
      EXPECT_EQ(c.model_reference, cell.model_point);
      EXPECT_EQ(c.votes, cell.votes);
      const Eigen::Isometry3f pose =
          poseFromLocalCoordinate(T_s, referenceFrame(model.points[cell.model_point], model.normals[cell.model_point]),
                                  q.alphaBinCentre(cell.alpha_bin));
      EXPECT_LT((pose.matrix() - c.T_camera_model.matrix()).cwiseAbs().maxCoeff(), 1e-5f);
    }
  }
  EXPECT_EQ(next, candidates.size()) << "extra candidates";
}

class VotingVsBruteForce : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937_64 rng(31);
    truth = randomPose(rng, 0.3f);
    truth.translation().z() += 0.8f;  // in front of the camera, as in a bin
    scene = transformedModel(model, truth);
  }
  const PreparedModel& model = smallModel();
  Eigen::Isometry3f truth;
  PreparedScene scene;
};

TEST_F(VotingVsBruteForce, WinnerOfEveryReferenceMatches) {
  ASSERT_GT(model.size(), 50u);
  ASSERT_LT(model.size(), 800u) << "the small model should stay small";
  const auto candidates = vote(model, scene, allPairs(1), nullptr, nullptr, 2);
  const auto expected = bruteForceVote(model, scene, 1);
  expectSameAsBruteForce(model, scene, candidates, expected);

  // The best-voted candidate is the known pose, up to half an alpha bin about the reference
  // normal (alpha is quantised; nothing else is, since the scene is the model itself).
  ASSERT_FALSE(candidates.empty());
  const auto best = std::min_element(candidates.begin(), candidates.end(),
                                     [](const PoseCandidate& a, const PoseCandidate& b) { return a.votes > b.votes; });
  const double half_bin_deg = 180.0 / model.quantizer().alphaBinCount();
  EXPECT_LE(rotationErrorDeg(best->T_camera_model.linear(), truth.linear()), half_bin_deg + 0.01);
  // The reference point itself is mapped exactly, the model origin within the half-bin turn.
  EXPECT_LT((best->T_camera_model * model.points[best->model_reference] - scene.points[best->scene_reference]).norm(),
            1e-5f);
  EXPECT_EQ(best->model_reference, best->scene_reference) << "scene point k is model point k";
  const float arm = (model.points[best->model_reference]).norm();  // model origin to the reference
  EXPECT_LE(translationError(best->T_camera_model, truth),
            arm * 2.0 * std::sin(testing::rad(half_bin_deg) / 2.0) + 1e-5);
  EXPECT_LT(translationError(best->T_camera_model, truth), 0.006) << "a few mm";

  // Most references vote for their own model point.
  std::size_t own = 0;
  for (const PoseCandidate& c : candidates) own += c.model_reference == c.scene_reference;
  EXPECT_GT(own, candidates.size() * 7 / 10);
}

TEST_F(VotingVsBruteForce, TopThreeOfEveryReferenceMatchAndThreadCountDoesNotMatter) {
  const auto one_thread = vote(model, scene, allPairs(3), nullptr, nullptr, 1);
  const auto two_threads = vote(model, scene, allPairs(3), nullptr, nullptr, 2);
  expectSameAsBruteForce(model, scene, two_threads, bruteForceVote(model, scene, 3));
  ASSERT_EQ(one_thread.size(), two_threads.size());
  for (std::size_t k = 0; k < one_thread.size(); ++k) {
    EXPECT_EQ(one_thread[k].scene_reference, two_threads[k].scene_reference);
    EXPECT_EQ(one_thread[k].model_reference, two_threads[k].model_reference);
    EXPECT_EQ(one_thread[k].votes, two_threads[k].votes);
    EXPECT_TRUE(one_thread[k].T_camera_model.matrix() == two_threads[k].T_camera_model.matrix());
  }
  // Ordered by reference, then by votes descending.
  for (std::size_t k = 1; k < two_threads.size(); ++k) {
    const auto& a = two_threads[k - 1];
    const auto& b = two_threads[k];
    EXPECT_TRUE(a.scene_reference < b.scene_reference ||
                (a.scene_reference == b.scene_reference && a.votes >= b.votes));
  }
}

TEST_F(VotingVsBruteForce, MinRelativeVotesDropsWeakLocalCoordinates) {
  VotingParams p = allPairs(5);
  p.min_relative_votes = 0.9f;
  const auto candidates = vote(model, scene, p, nullptr, nullptr, 2);
  const auto expected = bruteForceVote(model, scene, 5);
  std::size_t next = 0;
  for (std::size_t r = 0; r < scene.size(); ++r) {
    for (const Cell& cell : expected[r]) {
      if (cell.votes < 0.9f * static_cast<float>(expected[r].front().votes)) break;
      ASSERT_LT(next, candidates.size());
      EXPECT_EQ(candidates[next].scene_reference, r);
      EXPECT_EQ(candidates[next].model_reference, cell.model_point);
      EXPECT_EQ(candidates[next].votes, cell.votes);
      ++next;
    }
  }
  EXPECT_EQ(next, candidates.size());
}

TEST_F(VotingVsBruteForce, ReferenceFractionSelectsTheSampledReferences) {
  VotingParams p = allPairs(2);
  p.reference_fraction = 0.1f;
  p.seed = 77;
  const auto candidates = vote(model, scene, p, nullptr, nullptr, 2);
  const auto references = sampleIndices(scene.size(), 0.1f, 77);
  std::vector<uint32_t> seen;
  for (const auto& c : candidates) {
    if (seen.empty() || seen.back() != c.scene_reference) seen.push_back(c.scene_reference);
  }
  EXPECT_EQ(seen, references);
}

TEST(Voting, DegenerateScenesGiveNoCandidates) {
  const PreparedModel& model = smallModel();
  PreparedScene scene;
  EXPECT_TRUE(vote(model, scene, VotingParams{}).empty());
  scene.points.push_back({0, 0, 1});
  scene.normals.push_back({0, 0, -1});
  scene.source_index.push_back(0);
  EXPECT_TRUE(vote(model, scene, VotingParams{}).empty());
  // Two points farther apart than the model: no pair is within diam(M).
  scene.points.push_back({0, 0, 1 + 3 * model.diameter});
  scene.normals.push_back({0, 0, -1});
  scene.source_index.push_back(1);
  EXPECT_TRUE(vote(model, scene, allPairs(1), nullptr, nullptr, 1).empty());
}

TEST(SampleIndices, SeededSortedPrefixOfTheRequestedShare) {
  const auto all = sampleIndices(50, 1.0f, 3);
  ASSERT_EQ(all.size(), 50u);
  for (uint32_t i = 0; i < 50; ++i) EXPECT_EQ(all[i], i);

  const auto tenth = sampleIndices(1000, 0.1f, 3);
  EXPECT_EQ(tenth.size(), 100u);
  EXPECT_TRUE(std::is_sorted(tenth.begin(), tenth.end()));
  EXPECT_EQ(std::adjacent_find(tenth.begin(), tenth.end()), tenth.end()) << "no repeats";
  EXPECT_LT(tenth.back(), 1000u);
  EXPECT_EQ(tenth, sampleIndices(1000, 0.1f, 3)) << "same seed, same sample";
  EXPECT_NE(tenth, sampleIndices(1000, 0.1f, 4)) << "another seed, another sample";
  EXPECT_EQ(sampleIndices(7, 0.1f, 3).size(), 1u) << "rounded up: at least one";
  EXPECT_TRUE(sampleIndices(0, 0.5f, 3).empty());
}

}  // namespace
}  // namespace binpick::estimation
