// The emptying run's params check, emptying.json and its progress lines.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "binpick/core/error.hpp"
#include "binpick/emptying/emptying.hpp"
#include "binpick/estimation/result_json.hpp"

namespace binpick::emptying {
namespace {

using estimation::poseJson;

nlohmann::json pickJson(const PickRecord& pick) {
  return {{"cycle", pick.cycle},
          {"ok", pick.ok},
          {"reason", pick.reason},
          {"grasp", pick.grasp},
          {"grasp_name", pick.grasp_name},
          {"T_base_grasp", poseJson(pick.T_base_grasp)},
          {"T_base_part_true", pick.T_base_part_true ? poseJson(*pick.T_base_part_true) : nlohmann::json()}};
}

nlohmann::json cycleJson(const CycleRecord& cycle) {
  return {{"cycle", cycle.cycle},
          {"status", cycle.status},
          {"detail", cycle.detail},
          {"parts_before", cycle.parts_before},
          {"parts_after", cycle.parts_after},
          {"detections", cycle.detections},
          {"cycle_ms", cycle.cycle_ms},
          {"render_ms", cycle.render_ms}};
}

std::string seconds(double milliseconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f s", milliseconds / 1000.0);
  return text;
}

}  // namespace

void EmptyingParams::validate() const {
  const std::string owner = "EmptyingParams";
  pile.validate();
  photometry.validate();
  gripper.validate();
  truth.validate();
  core::requireField(std::isfinite(approach_distance) && approach_distance >= 0, owner, "approach_distance", ">= 0",
                     approach_distance);
  core::requireField(max_cycles >= 0, owner, "max_cycles", ">= 0", max_cycles);
  core::requireField(patience >= 1, owner, "patience", ">= 1", patience);
  core::requireField(web_port >= -1 && web_port <= 65535, owner, "web_port", "a port, 0 (any free) or -1 (none)",
                     web_port);
  core::requireField(!out_directory.empty(), owner, "out_directory", "given", "\"\"");
}

std::string emptyingEndName(EmptyingEnd end) {
  switch (end) {
    case EmptyingEnd::Empty: return "empty";
    case EmptyingEnd::Unreachable: return "unreachable";
    case EmptyingEnd::MaxCycles: break;
  }
  return "max_cycles";
}

void writeEmptyingJson(const std::string& path, const EmptyingReport& report) {
  nlohmann::json picks = nlohmann::json::array(), cycles = nlohmann::json::array(), left = nlohmann::json::array();
  for (const CycleRecord& cycle : report.cycles) {
    cycles.push_back(cycleJson(cycle));
    if (cycle.pick) picks.push_back(pickJson(*cycle.pick));
  }
  for (const PartLeft& part : report.left) {
    left.push_back({{"index", part.index},
                    {"T_base_part", poseJson(part.T_base_part)},
                    {"visible_fraction", part.visible_fraction},
                    {"wall_distance", part.wall_distance}});
  }
  const nlohmann::json json = {
      {"part", report.part},
      {"gripper", report.gripper},
      {"grasps", report.grasps},
      {"objects", report.objects},
      {"picked", report.picked},
      {"failed_picks", report.failed_picks},
      {"escaped", report.escaped},
      {"cycles", static_cast<int>(report.cycles.size())},
      {"end", emptyingEndName(report.end)},
      {"cycle_ms", {{"median", report.median_cycle_ms}, {"max", report.max_cycle_ms}}},
      {"picks", picks},
      {"left", left},
      {"cycle_log", cycles},
  };
  std::ofstream file(path);
  file << json.dump(2) << "\n";
  if (!file) throw core::Error(path + ": cannot write");
}

std::string summaryLine(const EmptyingReport& report) {
  std::string line = "cleared " + std::to_string(report.picked) + "/" + std::to_string(report.objects) + " in " +
                     std::to_string(report.cycles.size()) + " cycles, " + std::to_string(report.failed_picks) +
                     " failed picks, median cycle " + seconds(report.median_cycle_ms) + " (" +
                     emptyingEndName(report.end) + ")";
  if (!report.left.empty()) line += "; " + std::to_string(report.left.size()) + " left";
  if (report.escaped > 0) line += "; " + std::to_string(report.escaped) + " thrown out of the bin";
  return line;
}

std::string cycleLine(const CycleRecord& cycle) {
  std::string line = "cycle " + std::to_string(cycle.cycle) + ": " + std::to_string(cycle.parts_before) +
                     " in the bin, " + std::to_string(cycle.detections) + " detected, ";
  if (!cycle.pick) {
    line += cycle.status + (cycle.detail.empty() ? "" : " (" + cycle.detail + ")");
  } else {
    const PickRecord& pick = *cycle.pick;
    line += std::string(pick.ok ? "picked" : "FAILED") + " with " +
            (pick.grasp_name.empty() ? "grasp " + std::to_string(pick.grasp) : "\"" + pick.grasp_name + "\"") +
            (pick.ok ? "" : ": " + pick.reason);
  }
  return line + "; cycle " + seconds(cycle.cycle_ms) + ", render " + seconds(cycle.render_ms);
}

}  // namespace binpick::emptying
