#include "status_json.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

namespace binpick::web {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Labels of the orientation values as the robot's pendant shows them (core/orientation.hpp).
json orientationLabels(core::Orientation orientation) {
  switch (orientation) {
    case core::Orientation::Quaternion: return {"q1 (w)", "q2 (x)", "q3 (y)", "q4 (z)"};
    case core::Orientation::EulerZYX: return {"A", "B", "C"};
    case core::Orientation::FixedXYZ: return {"W", "P", "R"};
    case core::Orientation::RotationVector: return {"rx", "ry", "rz"};
    case core::Orientation::EulerXYZ: return {"rx", "ry", "rz"};
  }
  return json::array();
}

const char* orientationUnit(core::Orientation orientation) {
  switch (orientation) {
    case core::Orientation::Quaternion: return "";
    case core::Orientation::RotationVector: return "rad";
    default: return "deg";
  }
}

double rounded(double value, double step) { return std::round(value / step) * step; }

json pickJson(const cell::PickSummary& pick, std::size_t order, core::Orientation orientation) {
  const Eigen::Vector3d mm = pick.T_base_grasp.translation() * 1000.0;
  json values = json::array();
  for (double v : core::orientationValues(pick.T_base_grasp.linear(), orientation)) values.push_back(rounded(v, 1e-4));
  return {{"order", order},
          {"object", pick.object},
          {"grasp", pick.grasp},
          {"grasp_name", pick.grasp_name},
          {"position_mm", {rounded(mm.x(), 0.01), rounded(mm.y(), 0.01), rounded(mm.z(), 0.01)}},
          {"orientation", values},
          {"tilt_deg", rounded(pick.tilt_deg, 0.01)},
          {"lean_deg", rounded(pick.lean_deg, 0.01)},
          {"score", rounded(pick.score, 1e-4)},
          {"coverage", rounded(pick.coverage, 1e-4)},
          {"rank", rounded(pick.rank, 1e-4)},
          {"clearance_mm", rounded(pick.clearance * 1000.0, 0.01)}};
}

json rejectedJson(const picking::PickRejections& r) {
  return {{"invalid", r.invalid}, {"avoided", r.avoided}, {"tilt", r.tilt},
          {"bin", r.bin},         {"cloud", r.cloud},     {"seal", r.seal}};
}

json timingJson(const cell::CycleTimings& t) {
  return {{"capture", rounded(t.capture, 0.1)},
          {"reconstruct", rounded(t.reconstruct, 0.1)},
          {"detect", rounded(t.detect, 0.1)},
          {"plan", rounded(t.plan, 0.1)},
          {"total", rounded(t.total, 0.1)}};
}

json fileUrl(const std::optional<cell::SavedCycleDirectory>& directory, uint64_t cycle, const char* file) {
  std::error_code error;
  if (!directory || !fs::is_regular_file(fs::path(directory->path) / file, error)) return nullptr;
  return "/api/cycles/" + std::to_string(cycle) + "/" + file;
}

json sourceJson(const cell::CaptureHealth& c) {
  return {{"mode", c.mode},
          {"description", c.source},
          {"captures", c.captures},
          {"failures", c.failures},
          {"last_capture", c.last_capture ? json(isoTime(*c.last_capture)) : json(nullptr)},
          {"last_ok", c.last_ok},
          {"last_error", c.last_error},
          {"calibration_ok", c.calibration_problem.empty()},
          {"calibration_problem", c.calibration_problem},
          {"hand_eye", c.hand_eye}};
}

json robotsJson(const std::vector<robot::ConnectedClient>& robots, std::chrono::system_clock::time_point now) {
  json list = json::array();
  for (const robot::ConnectedClient& r : robots) {
    list.push_back({{"id", r.id},
                    {"peer", r.peer},
                    {"connected_since", isoTime(r.since)},
                    {"connected_s", rounded(std::chrono::duration<double>(now - r.since).count(), 0.1)}});
  }
  return list;
}

json logJson(const std::vector<LogLine>& lines) {
  json list = json::array();
  for (const LogLine& line : lines) {
    list.push_back({{"time", isoTime(line.time)}, {"level", line.level}, {"logger", line.logger}, {"text", line.text}});
  }
  return list;
}

// The newest saved cycle that has an overlay: what the page shows while the latest is being saved.
json latestOverlayJson(const std::vector<cell::SavedCycleDirectory>& saved) {
  std::error_code error;
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) {
    if (!fs::is_regular_file(fs::path(it->path) / "overlay.png", error)) continue;
    return {{"cycle", it->cycle}, {"url", "/api/cycles/" + std::to_string(it->cycle) + "/overlay.png"}};
  }
  return nullptr;
}

}  // namespace

std::string stateName(const cell::CellReport& report) {
  switch (report.state) {
    case cell::CellState::Capturing: return "capturing";
    case cell::CellState::Computing:
      switch (report.stage) {
        case cell::CycleStage::Reconstructing: return "reconstructing";
        case cell::CycleStage::Detecting: return "detecting";
        case cell::CycleStage::Planning: return "planning";
      }
      return "computing";
    case cell::CellState::Idle: break;
  }
  return report.picks_waiting > 0 ? "waiting_for_robot" : "idle";
}

std::string isoTime(std::chrono::system_clock::time_point time) {
  const auto since_epoch = std::chrono::duration_cast<std::chrono::milliseconds>(time.time_since_epoch()).count();
  const std::time_t seconds = static_cast<std::time_t>(since_epoch / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[40];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(text + n, sizeof text - n, ".%03dZ", static_cast<int>(since_epoch % 1000));
  return text;
}

std::optional<cell::SavedCycleDirectory> savedDirectoryOf(const cell::CycleSummary& cycle,
                                                          const std::vector<cell::SavedCycleDirectory>& saved) {
  // Directory names count whole seconds: one second of slack.
  const auto earliest = cycle.started - std::chrono::seconds(1);
  for (auto it = saved.rbegin(); it != saved.rend(); ++it) {
    if (it->cycle == cycle.number) {
      if (it->saved_at >= earliest) return *it;
      return std::nullopt;  // the newest of that number is older than the cycle: another run's
    }
  }
  return std::nullopt;
}

json cycleJson(const cell::CycleSummary& cycle, const std::vector<cell::SavedCycleDirectory>& saved,
               core::Orientation orientation, bool picks) {
  const std::optional<cell::SavedCycleDirectory> directory = savedDirectoryOf(cycle, saved);
  json out = {{"number", cycle.number},
              {"time", isoTime(cycle.started)},
              {"recipe", cycle.recipe},
              {"status", robot::statusName(cycle.status)},
              {"detail", cycle.detail},
              {"counts",
               {{"detected", cycle.parts_detected},
                {"picks", cycle.picks.size()},
                {"low_coverage", cycle.low_coverage},
                {"rejected", cycle.rejected.total()},
                {"undeliverable", cycle.undeliverable.size()}}},
              {"bin_points", cycle.bin_points},
              {"rejected", rejectedJson(cycle.rejected)},
              {"undeliverable", cycle.undeliverable},
              {"timing_ms", timingJson(cycle.timing_ms)},
              {"overlay", fileUrl(directory, cycle.number, "overlay.png")},
              {"cloud", fileUrl(directory, cycle.number, "cloud.ply")}};
  if (picks) {
    json list = json::array();
    for (std::size_t i = 0; i < cycle.picks.size(); ++i) list.push_back(pickJson(cycle.picks[i], i + 1, orientation));
    out["picks"] = list;
  }
  return out;
}

json statusJson(const StatusInputs& in) {
  const cell::CellReport& report = in.report;
  const auto& recent = *report.recent;
  return {{"time", isoTime(in.now)},
          {"uptime_s", rounded(std::chrono::duration<double>(in.now - report.started).count(), 0.1)},
          {"state", stateName(report)},
          {"cycle", report.cycle},
          {"recipe", report.recipe},
          {"recipes", report.recipes},
          {"picks_waiting", report.picks_waiting},
          {"orientation",
           {{"convention", core::orientationName(report.orientation)},
            {"labels", orientationLabels(report.orientation)},
            {"unit", orientationUnit(report.orientation)}}},
          {"source", sourceJson(report.capture)},
          {"robots", robotsJson(in.robots, in.now)},
          {"artefacts_saved", report.artefact_directory.has_value()},
          {"last_cycle", recent.empty() ? json(nullptr) : cycleJson(recent.back(), in.saved, report.orientation, true)},
          {"latest_overlay", latestOverlayJson(in.saved)},
          {"log", logJson(in.log)}};
}

json cyclesJson(const cell::CellReport& report, const std::vector<cell::SavedCycleDirectory>& saved) {
  json list = json::array();
  for (auto it = report.recent->rbegin(); it != report.recent->rend(); ++it) {
    list.push_back(cycleJson(*it, saved, report.orientation, false));
  }
  return {{"cycles", list}};
}

}  // namespace binpick::web
