#include "voting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include "binpick/core/error.hpp"
#include "neighbour_grid.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

struct LocalCoordinate {
  uint32_t votes = 0;
  uint32_t model_point = 0;
  int alpha_bin = 0;
};

// The accumulator of one reference point: votes per (model point, alpha bin).
class Accumulator {
 public:
  Accumulator(std::size_t model_points, int alpha_bins)
      : alpha_bins_(alpha_bins), votes_(model_points * static_cast<std::size_t>(alpha_bins), 0) {}

  void clear() { std::fill(votes_.begin(), votes_.end(), 0u); }
  void add(uint32_t model_point, int alpha_bin) {
    ++votes_[static_cast<std::size_t>(model_point) * alpha_bins_ + alpha_bin];
  }

  // The `count` local coordinates with most votes, best first (ties: lower index first). Most
  // cells hold a few votes and cannot enter once `count` are kept: blocks whose most-voted cell
  // does not beat the last kept are passed over in one comparison (a vectorised maximum).
  std::vector<LocalCoordinate> top(int count) const {
    std::vector<LocalCoordinate> best;
    uint32_t floor = 0;  // a cell must have more votes than this to enter
    const std::size_t cells = votes_.size();
    for (std::size_t block = 0; block < cells; block += kBlock) {
      const std::size_t end = std::min(cells, block + kBlock);
      uint32_t most = 0;
      for (std::size_t cell = block; cell < end; ++cell) most = std::max(most, votes_[cell]);
      if (most <= floor) continue;
      for (std::size_t cell = block; cell < end; ++cell) {
        const uint32_t v = votes_[cell];
        if (v <= floor) continue;
        LocalCoordinate lc{v, static_cast<uint32_t>(cell / alpha_bins_), static_cast<int>(cell % alpha_bins_)};
        auto at =
            std::upper_bound(best.begin(), best.end(), lc,
                             [](const LocalCoordinate& a, const LocalCoordinate& b) { return a.votes > b.votes; });
        best.insert(at, lc);
        if (static_cast<int>(best.size()) > count) best.pop_back();
        if (static_cast<int>(best.size()) == count) floor = best.back().votes;
      }
    }
    return best;
  }

 private:
  static constexpr std::size_t kBlock = 32;
  int alpha_bins_;
  std::vector<uint32_t> votes_;
};

}  // namespace

void VotingParams::validate() const {
  const char* owner = "detection.voting";
  core::requireField(reference_fraction > 0.0f && reference_fraction <= 1.0f, owner, "reference_fraction", "in (0, 1]",
                     reference_fraction);
  core::requireField(referred_fraction > 0.0f && referred_fraction <= 1.0f, owner, "referred_fraction", "in (0, 1]",
                     referred_fraction);
  core::requireField(poses_per_reference >= 1 && poses_per_reference <= 100, owner, "poses_per_reference",
                     "in [1, 100]", poses_per_reference);
  core::requireField(min_relative_votes >= 0.0f && min_relative_votes <= 1.0f, owner, "min_relative_votes", "in [0, 1]",
                     min_relative_votes);
}

std::vector<uint32_t> sampleIndices(std::size_t count, float fraction, uint64_t seed) {
  std::vector<uint32_t> all(count);
  std::iota(all.begin(), all.end(), 0u);
  if (fraction >= 1.0f) return all;
  std::shuffle(all.begin(), all.end(), std::mt19937_64(seed));
  const auto keep = static_cast<std::size_t>(std::ceil(fraction * static_cast<float>(count)));
  all.resize(std::min(keep, count));
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<PoseCandidate> vote(const PreparedModel& model, const PreparedScene& scene, const VotingParams& params,
                                const core::CancelFlag* cancel, const BoundaryVotes* boundary, int threads) {
  params.validate();
  if (scene.size() < 2 || model.size() == 0) return {};
  const PpfQuantizer quantizer = model.quantizer();
  const std::vector<uint32_t> references = sampleIndices(scene.size(), params.reference_fraction, params.seed);
  const std::vector<uint32_t> referred =
      sampleIndices(scene.size(), params.referred_fraction, params.seed ^ 0x9e3779b97f4a7c15ULL);
  const NeighbourGrid grid(scene.points, referred, model.diameter);
  const bool with_boundary = boundary != nullptr && boundary->scene.size() > 0;
  std::vector<uint32_t> all_boundary_points;
  if (with_boundary) {
    all_boundary_points.resize(boundary->scene.size());
    std::iota(all_boundary_points.begin(), all_boundary_points.end(), 0u);
  }
  const NeighbourGrid boundary_grid(with_boundary ? boundary->scene.points : scene.points, all_boundary_points,
                                    model.diameter);

  // Model reference frames T_m, computed once.
  std::vector<Eigen::Isometry3f> model_frames(model.size());
  for (std::size_t i = 0; i < model.size(); ++i) model_frames[i] = referenceFrame(model.points[i], model.normals[i]);

  const int np = params.poses_per_reference;
  std::vector<PoseCandidate> slots(references.size() * static_cast<std::size_t>(np));
  std::vector<int> filled(references.size(), 0);
  const float max_distance_sq = model.diameter * model.diameter;

#pragma omp parallel num_threads(core::resolveThreadCount(threads))
  {
    // Only the references of the table (one turn of a symmetric part) can receive votes.
    Accumulator accumulator(model.referenceCount(), quantizer.alphaBinCount());
#pragma omp for schedule(dynamic, 4)
    for (std::size_t r = 0; r < references.size(); ++r) {
      if (core::isCancelled(cancel)) continue;  // the rest is skipped; the throw comes after the region
      const uint32_t s_r = references[r];
      const Eigen::Vector3f& p_r = scene.points[s_r];
      const Eigen::Vector3f& n_r = scene.normals[s_r];
      const Eigen::Isometry3f T_s = referenceFrame(p_r, n_r);
      accumulator.clear();
      // Every model pair under the scene pair's key votes for its local coordinate (model
      // reference, alpha): alpha = alpha_s - alpha_m rotates the model pair onto the scene pair (eq. 2).
      const auto castVotes = [&](const PpfHashTable& table, int64_t key, const Eigen::Vector3f& referred_point) {
        const PpfHashTable::Range matches = table.lookup(key);
        if (matches.begin == matches.end) return;
        const float scene_angle = planarAngle(T_s * referred_point);
        for (const PairEntry* e = matches.begin; e != matches.end; ++e) {
          accumulator.add(e->reference, quantizer.alphaBinOfDifference(scene_angle, e->reference_angle));
        }
      };
      grid.forEachNear(p_r, [&](uint32_t s_j) {
        const Eigen::Vector3f& p_j = scene.points[s_j];
        if (s_j == s_r || (p_j - p_r).squaredNorm() > max_distance_sq) return;
        castVotes(model.table, quantizer.pairKey(p_r, n_r, p_j, scene.normals[s_j]), p_j);
      });
      if (with_boundary) {
        // Surface-to-boundary pairs (Choi et al. 2012): the same reference frame and alpha, the
        // boundary point's line direction in place of a normal.
        boundary_grid.forEachNear(p_r, [&](uint32_t b) {
          const Eigen::Vector3f& p_b = boundary->scene.points[b];
          if ((p_b - p_r).squaredNorm() > max_distance_sq) return;
          castVotes(boundary->model.table, quantizer.boundaryPairKey(p_r, n_r, p_b, boundary->scene.directions[b]),
                    p_b);
        });
      }
      const std::vector<LocalCoordinate> best = accumulator.top(np);
      int kept = 0;
      for (const LocalCoordinate& lc : best) {
        if (lc.votes < params.min_relative_votes * static_cast<float>(best.front().votes)) break;
        PoseCandidate& c = slots[r * np + kept++];
        c.T_camera_model =
            poseFromLocalCoordinate(T_s, model_frames[lc.model_point], quantizer.alphaBinCentre(lc.alpha_bin));
        c.votes = lc.votes;
        c.scene_reference = s_r;
        c.model_reference = lc.model_point;
      }
      filled[r] = kept;
    }
  }

  core::throwIfCancelled(cancel, "during voting");
  std::vector<PoseCandidate> candidates;
  candidates.reserve(slots.size());
  for (std::size_t r = 0; r < references.size(); ++r) {
    for (int k = 0; k < filled[r]; ++k) candidates.push_back(slots[r * np + k]);
  }
  return candidates;
}

}  // namespace binpick::estimation
