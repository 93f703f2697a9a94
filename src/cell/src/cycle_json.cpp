// detections.json of a saved cycle: what was found, what the robot was sent, and how long it took.
#include <nlohmann/json.hpp>

#include "artefact_saver.hpp"
#include "binpick/estimation/result_json.hpp"

namespace binpick::cell {
namespace {

using estimation::poseJson;

// The confident detections that were not picked, by the reason (picking.hpp).
nlohmann::json rejectedJson(const picking::PickRejections& r) {
  return {{"invalid", r.invalid}, {"avoided", r.avoided}, {"tilt", r.tilt},
          {"bin", r.bin},         {"cloud", r.cloud},     {"seal", r.seal}};
}

}  // namespace

std::string cycleJson(const SavedCycle& cycle) {
  const CycleOutcome& outcome = cycle.outcome;
  nlohmann::json picks = nlohmann::json::array();
  for (const picking::Pick& pick : outcome.picks) {
    picks.push_back({{"object", pick.object},
                     {"grasp", pick.grasp},
                     {"tilt_deg", pick.tilt_deg},
                     {"lean_deg", pick.lean_deg},
                     {"clearance", pick.clearance},
                     {"rank", pick.rank},
                     {"T_base_grasp", poseJson(pick.T_base_grasp)}});
  }
  const CycleTimings& t = outcome.timing_ms;
  nlohmann::json json = {
      {"cycle", cycle.number},
      {"recipe", cycle.setup->recipes.at(static_cast<std::size_t>(cycle.recipe)).name},
      {"status", robot::statusName(outcome.status)},
      {"detail", outcome.detail},
      {"bin_points", outcome.bin_points},
      {"picks", picks},
      {"rejected", rejectedJson(outcome.rejected)},
      {"undeliverable", outcome.undeliverable},  // picks left out: the robot could not be sent them
      {"timing_ms",
       {{"capture", t.capture},
        {"reconstruct", t.reconstruct},
        {"detect", t.detect},
        {"plan", t.plan},
        {"total", t.total}}},
      {"detection", estimation::toJson(outcome.detection)},
  };
  return json.dump(2);
}

}  // namespace binpick::cell
