#pragma once
// The calibration board on the command line, shared by `calibrate rig` and `calibrate hand-eye`:
//   --board charuco|chessboard  --squares 9x7  --square-mm 30  --marker-mm 22
//   --dictionary DICT_5X5_100
// Every option is optional; the defaults are the virtual cell's board (BoardLayout's defaults).
#include <set>
#include <string>

#include "arguments.hpp"
#include "binpick/calibration/board_layout.hpp"

namespace binpick::cli {

// The valued options above, to merge into a command's own set.
const std::set<std::string>& boardOptionNames();

// The layout the options describe, validated; throws core::Error naming the option.
calibration::BoardLayout boardLayoutFromArguments(const Arguments& args);

}  // namespace binpick::cli
