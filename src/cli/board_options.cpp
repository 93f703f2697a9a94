// Board options: parsed once for every calibration command.
#include "board_options.hpp"

#include <utility>

#include "binpick/core/error.hpp"

namespace binpick::cli {
namespace {

std::string sizeText(int x, int y) { return std::to_string(x) + "x" + std::to_string(y); }

// "9x7" -> {9, 7}; `option` names the option in the error.
std::pair<int, int> parseSize(const std::string& option, const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw core::Error(option + " must be COLUMNSxROWS, e.g. 9x7 (got '" + text + "')");
  return {parseInteger(option + " columns", text.substr(0, x)), parseInteger(option + " rows", text.substr(x + 1))};
}

// Each convention's error names the other: 1x1 inner corners would be 2x2 squares, both too few.
void setSize(const Arguments& args, calibration::BoardLayout& layout) {
  if (const auto squares = args.value("--squares")) {
    const auto [x, y] = parseSize("--squares", *squares);
    if (x < 3 || y < 3) {
      throw core::Error("board options: --squares " + *squares + ": a board needs at least 3x3 squares (2x2 inner" +
                        " corners); for the inner corners use --inner-corners");
    }
    layout.squares_x = x;
    layout.squares_y = y;
  }
  if (const auto inner = args.value("--inner-corners")) {
    const auto [x, y] = parseSize("--inner-corners", *inner);
    if (x < 2 || y < 2) {
      throw core::Error("board options: --inner-corners " + *inner +
                        ": a chessboard needs at least 2x2 inner corners (3x3 squares); for the squares use --squares");
    }
    layout.squares_x = x + 1;
    layout.squares_y = y + 1;
  }
}

}  // namespace

CLI::Option_group& addBoardOptions(CLI::App& command) {
  CLI::Option_group& group = *command.add_option_group("Board options");
  addText(group, "--board", "TYPE", "charuco (default) or chessboard");
  CLI::Option* squares = addText(group, "--squares", "CxR", "Squares across and down (default 9x7)");
  CLI::Option* inner = addText(group, "--inner-corners", "CxR",
                               "Or: inner corners across and down, OpenCV's chessboard size (squares - 1, e.g. 8x6)");
  squares->excludes(inner);
  addNumber(group, "--square-mm", "MM", "Side of a square in mm (default 30)");
  addNumber(group, "--marker-mm", "MM", "ChArUco: side of a marker in mm (default 22)");
  addText(group, "--dictionary", "NAME", "ChArUco: ArUco dictionary (default DICT_5X5_100)");
  return group;
}

calibration::BoardLayout boardLayoutFromArguments(const Arguments& args) {
  calibration::BoardLayout layout;
  if (const auto type = args.value("--board")) layout.type = calibration::boardTypeFromName(*type);
  setSize(args, layout);
  if (const auto size = args.number("--square-mm")) layout.square_size = *size / 1000.0;
  if (const auto size = args.number("--marker-mm")) layout.marker_size = *size / 1000.0;
  if (const auto name = args.value("--dictionary")) layout.dictionary = *name;
  try {
    layout.validate();
  } catch (const core::Error& e) {
    throw core::Error(std::string("board options: ") + e.what());
  }
  return layout;
}

std::string boardSizeHint(const Arguments& args, const calibration::BoardDetection& detection) {
  const int x = detection.seen_inner_x, y = detection.seen_inner_y;
  if (x <= 0 || y <= 0) return "";
  const std::string inner = "--inner-corners " + sizeText(x, y);
  const std::string squares = "--squares " + sizeText(x + 1, y + 1);
  // The numbers typed, read in the other convention, are the board seen: the likely slip.
  if (args.value("--squares") == sizeText(x, y)) return "did you mean " + inner + "?";
  if (args.value("--inner-corners") == sizeText(x + 1, y + 1)) return "did you mean " + squares + "?";
  return "the image holds a chessboard of " + sizeText(x, y) + " inner corners: " + inner + " (or " + squares + ")";
}

}  // namespace binpick::cli
