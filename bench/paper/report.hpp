#pragma once
// Markdown tables in the layout of the paper's Tables II and III: parts down, methods across,
// the average over parts at the bottom.
#include <string>
#include <vector>

#include "experiment.hpp"

namespace binpick::bench {

struct TableLayout {
  std::vector<std::string> parts;    // rows, in order
  std::vector<std::string> methods;  // columns, in order; the first is the reference of "relative time"
  CloudInput input = CloudInput::Exact;
};

std::string recognitionTable(const Tallies& tallies, const TableLayout& layout);  // Table II
std::string speedTable(const Tallies& tallies, const TableLayout& layout);        // Table III
// Precision (correct / detections) and recall (found / objects at least half visible), "P / R".
std::string precisionRecallTable(const Tallies& tallies, const TableLayout& layout);
// Wrong detections among each scene's first 10, "W in S of N scenes".
std::string earlyWrongTable(const Tallies& tallies, const TableLayout& layout);
// binpick's methods: ms per object of each stage.
std::string stageTable(const Tallies& tallies, const TableLayout& layout);

}  // namespace binpick::bench
