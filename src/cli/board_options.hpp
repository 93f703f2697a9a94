#pragma once
// The calibration board on the command line, shared by `calibrate rig` and `calibrate hand-eye`,
// in the option group "Board options":
//   --board charuco|chessboard  --squares 9x7  --square-mm 30  --marker-mm 22
//   --dictionary DICT_5X5_100
// Every option is optional; the defaults are the virtual cell's board (BoardLayout's defaults).
#include <CLI/CLI.hpp>

#include "arguments.hpp"
#include "binpick/calibration/board_layout.hpp"

namespace binpick::cli {

// Declares the options above on `command`; returns their group.
CLI::Option_group& addBoardOptions(CLI::App& command);

// The layout the options describe, validated; throws core::Error naming the option.
calibration::BoardLayout boardLayoutFromArguments(const Arguments& args);

}  // namespace binpick::cli
