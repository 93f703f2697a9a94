#pragma once
// The calibration board on the command line, shared by `calibrate rig` and `calibrate hand-eye`,
// in the option group "Board options":
//   --board charuco|chessboard  --squares 9x7 | --inner-corners 8x6  --square-mm 30  --marker-mm 22
//   --dictionary DICT_5X5_100
// A board's size is given either as its squares (binpick's and ChArUco's convention) or as its
// inner corners (OpenCV's chessboard convention, one fewer each way). Every option is optional;
// the defaults are the virtual cell's board (BoardLayout's defaults).
#include <CLI/CLI.hpp>
#include <string>

#include "arguments.hpp"
#include "binpick/calibration/board_detection.hpp"
#include "binpick/calibration/board_layout.hpp"

namespace binpick::cli {

// Declares the options above on `command`; returns their group.
CLI::Option_group& addBoardOptions(CLI::App& command);

// The layout the options describe, validated; throws core::Error naming the option.
calibration::BoardLayout boardLayoutFromArguments(const Arguments& args);

// For a chessboard not found where one of another size was seen (BoardDetection::seen_inner_x):
// the option that describes the board seen, in the convention the user chose ("did you mean
// --inner-corners 9x7?" for --squares 9x7 on a board of 9 x 7 inner corners); empty otherwise.
std::string boardSizeHint(const Arguments& args, const calibration::BoardDetection& detection);

}  // namespace binpick::cli
