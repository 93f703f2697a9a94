#pragma once
// DIR/truth/board.json of a calibration sequence. Internal to binpick::simulation.
#include <string>

#include "binpick/simulation/calibration_sequence.hpp"

namespace binpick::simulation::detail {

constexpr int kBoardTruthVersion = 1;

// The board file's path in a sequence directory.
std::string boardTruthPath(const std::string& directory);

// Written through a temporary file and a rename. Throws core::Error naming the file when it
// cannot be written.
void writeBoardTruth(const std::string& path, const CalibrationTruth& truth);

}  // namespace binpick::simulation::detail
