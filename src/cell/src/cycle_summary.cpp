#include "cycle_summary.hpp"

#include <cmath>

namespace binpick::cell {

CycleSummary summarizeCycle(uint64_t cycle, const CellSetup& setup, int recipe_index, const CycleOutcome& outcome,
                            std::chrono::system_clock::time_point finished) {
  const Recipe& recipe = setup.recipes.at(static_cast<std::size_t>(recipe_index));
  CycleSummary summary;
  summary.number = cycle;
  summary.started = finished - std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                   std::chrono::duration<double, std::milli>(outcome.timing_ms.total));
  summary.recipe = recipe.name;
  summary.status = outcome.status;
  summary.detail = outcome.detail;
  summary.parts_detected = outcome.T_base_objects.size();
  for (const estimation::Detection& detection : outcome.detection.detections) {
    if (detection.coverage < setup.config.limits.min_pick_coverage) ++summary.low_coverage;
  }
  summary.bin_points = outcome.bin_points;
  for (const picking::Pick& pick : outcome.picks) {
    PickSummary p;
    p.object = pick.object;
    p.grasp = pick.grasp;
    const auto& grasps = recipe.picking.grasps;
    if (pick.grasp >= 0 && static_cast<std::size_t>(pick.grasp) < grasps.size())
      p.grasp_name = grasps[static_cast<std::size_t>(pick.grasp)].name;
    p.T_base_grasp = pick.T_base_grasp;
    p.tilt_deg = pick.tilt_deg;
    p.lean_deg = pick.lean_deg;
    p.clearance = pick.clearance;
    p.rank = pick.rank;
    const auto& detections = outcome.detection.detections;
    if (pick.object >= 0 && static_cast<std::size_t>(pick.object) < detections.size()) {
      p.score = detections[static_cast<std::size_t>(pick.object)].score;
      p.coverage = detections[static_cast<std::size_t>(pick.object)].coverage;
    }
    summary.picks.push_back(std::move(p));
  }
  summary.rejected = outcome.rejected;
  summary.undeliverable = outcome.undeliverable;
  summary.timing_ms = outcome.timing_ms;
  return summary;
}

std::shared_ptr<const std::deque<CycleSummary>> withCycle(const std::deque<CycleSummary>& recent, CycleSummary cycle) {
  auto next = std::make_shared<std::deque<CycleSummary>>(recent);
  next->push_back(std::move(cycle));
  while (next->size() > kReportedCycles) next->pop_front();
  return next;
}

}  // namespace binpick::cell
