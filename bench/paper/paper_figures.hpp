#pragma once
// The benchmark's figures: each section writes its PNG plots into `dir` and returns its markdown
// (a table of the plotted numbers and the image link).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "scaling.hpp"
#include "selection_timing.hpp"

namespace binpick::bench {

// The paper's Figure 5, averaged over the parts' curves; one row per part at the last pick.
std::string selectionSection(const std::vector<std::pair<std::string, SelectionCurves>>& curves,
                             const std::filesystem::path& dir);

std::string scalingSection(const std::string& part, const ScalingResults& results, const std::filesystem::path& dir);

// The processor's model name, for the record of where figures were measured.
std::string cpuName();

}  // namespace binpick::bench
