#include "selection_timing.hpp"

#include <chrono>
#include <functional>
#include <optional>

#include "binpick/core/stopwatch.hpp"
#include "selection.hpp"
#include "verification.hpp"
#include "voting.hpp"
#include "voxel_grid.hpp"

namespace binpick::bench {
namespace {

using estimation::VerifiedCandidate;

// The remaining candidate with the highest score (ties: the lower index), as `score` rates it.
std::optional<uint32_t> bestRemaining(const std::vector<VerifiedCandidate>& candidates,
                                      const std::vector<uint8_t>& taken,
                                      const std::function<uint32_t(const VerifiedCandidate&)>& score) {
  std::optional<uint32_t> best;
  uint32_t best_score = 0;
  for (uint32_t i = 0; i < candidates.size(); ++i) {
    if (taken[i]) continue;
    const uint32_t s = score(candidates[i]);
    if (!best || s > best_score) {
      best = i;
      best_score = s;
    }
  }
  return best;
}

// Picks with `score` until `picks` are made or no candidate is left; the picked candidates' SS(P)
// stop existing (Algorithm 1 lines 2-6).
void exhaustivePicks(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points, int picks,
                     const std::function<uint32_t(const VerifiedCandidate&, const std::vector<uint8_t>&)>& score,
                     std::vector<double>& ms, std::vector<uint32_t>& picked) {
  std::vector<uint8_t> exist(scene_points, 1), taken(candidates.size(), 0);
  const core::Stopwatch stopwatch;
  for (int k = 0; k < picks; ++k) {
    const auto best = bestRemaining(candidates, taken, [&](const VerifiedCandidate& c) { return score(c, exist); });
    if (!best) break;
    taken[*best] = 1;
    for (uint32_t s : candidates[*best].support) exist[s] = 0;
    ms.push_back(stopwatch.elapsedMs());
    picked.push_back(*best);
  }
}

void algorithm1Picks(const std::vector<VerifiedCandidate>& candidates, std::size_t scene_points, int picks,
                     SelectionCurves& out) {
  const core::Stopwatch stopwatch;
  estimation::MultipleSelection selection(candidates, scene_points);
  for (int k = 0; k < picks; ++k) {
    const auto pick = selection.next();
    if (!pick) break;
    selection.removeExplained(candidates[pick->candidate].support);
    out.algorithm1_ms.push_back(stopwatch.elapsedMs());
    out.algorithm1_picks.push_back(pick->candidate);
  }
}

}  // namespace

SelectionCurves measureSelection(const estimation::PreparedModel& model, const io::PointCloud& cloud,
                                 const estimation::CropBox& crop, int picks, int threads) {
  estimation::SceneParams scene_params;
  scene_params.crop = crop;
  const estimation::PreparedScene scene = estimation::prepareScene(cloud, model, scene_params, threads);
  const estimation::VerificationParams verification;
  const estimation::SceneVoxelGrid grid(scene.points, verification.voxel_size_ratio * model.step);
  const std::vector<VerifiedCandidate> candidates =
      estimation::verify(estimation::vote(model, scene, estimation::VotingParams{}, nullptr, nullptr, threads), model,
                         scene, grid, verification, nullptr, threads);

  SelectionCurves out;
  out.scene_points = scene.size();
  out.candidates = candidates.size();
  algorithm1Picks(candidates, scene.size(), picks, out);
  exhaustivePicks(
      candidates, scene.size(), picks,
      [](const VerifiedCandidate& c, const std::vector<uint8_t>& exist) {
        return estimation::existingCount(c.support, exist);
      },
      out.rescore_all_ms, out.rescore_all_picks);
  // Verification as the detector runs it (normals not checked: max_normal_angle_deg = 180).
  exhaustivePicks(
      candidates, scene.size(), picks,
      [&](const VerifiedCandidate& c, const std::vector<uint8_t>& exist) {
        return estimation::existingCount(
            estimation::correspondingScenePoints(model, c.T_camera_model, grid, scene.normals, -1.0f), exist);
      },
      out.reverify_all_ms, out.reverify_all_picks);
  return out;
}

}  // namespace binpick::bench
