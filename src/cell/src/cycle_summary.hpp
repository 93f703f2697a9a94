#pragma once
// Internal: a finished cycle as the cell's report keeps it (cell_report.hpp).
#include <chrono>

#include "binpick/cell/cell_report.hpp"
#include "binpick/cell/cell_setup.hpp"

namespace binpick::cell {

CycleSummary summarizeCycle(uint64_t cycle, const CellSetup& setup, int recipe_index, const CycleOutcome& outcome,
                            std::chrono::system_clock::time_point finished);

// `recent` with `cycle` appended, the oldest dropped beyond kReportedCycles.
std::shared_ptr<const std::deque<CycleSummary>> withCycle(const std::deque<CycleSummary>& recent, CycleSummary cycle);

}  // namespace binpick::cell
