#pragma once
// The web view's JSON (docs/binpickd.md, "Web view"): the cell's report, its robots, its saved
// cycles and its recent log lines, turned into the documents of /api/status and /api/cycles.
// Stateless functions: thread-safe.
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/cell/cell_report.hpp"
#include "binpick/robot/robot_server.hpp"
#include "binpick/web/log_ring.hpp"

namespace binpick::web {

// "idle", "capturing", "reconstructing", "detecting", "planning", or "waiting_for_robot" (idle
// with picks of the latest cycle not fetched yet).
std::string stateName(const cell::CellReport& report);

// "2026-12-01T16:15:00.123Z"
std::string isoTime(std::chrono::system_clock::time_point time);

// The saved directory of `cycle`, when it is the newest saved under that number and was saved
// after the cycle began (cycle numbers start again after a restart). Nullopt: not saved.
std::optional<cell::SavedCycleDirectory> savedDirectoryOf(const cell::CycleSummary& cycle,
                                                          const std::vector<cell::SavedCycleDirectory>& saved);

// One cycle: number, time, recipe, status, detail, counts, rejected, timing_ms and the URLs of
// its saved overlay and cloud (null when not saved). With `picks`, its picks too, the pose in
// the robot's orientation convention.
nlohmann::json cycleJson(const cell::CycleSummary& cycle, const std::vector<cell::SavedCycleDirectory>& saved,
                         core::Orientation orientation, bool picks);

struct StatusInputs {
  const cell::CellReport& report;
  std::vector<robot::ConnectedClient> robots;
  std::vector<cell::SavedCycleDirectory> saved;  // oldest first
  std::vector<LogLine> log;                      // oldest first
  std::chrono::system_clock::time_point now;
};

nlohmann::json statusJson(const StatusInputs& inputs);
// {"cycles": [...]}: the recent cycles, newest first, without their picks.
nlohmann::json cyclesJson(const cell::CellReport& report, const std::vector<cell::SavedCycleDirectory>& saved);

}  // namespace binpick::web
