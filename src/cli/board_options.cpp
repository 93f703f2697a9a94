// Board options: parsed once for every calibration command.
#include "board_options.hpp"

#include "binpick/core/error.hpp"

namespace binpick::cli {
namespace {

// "9x7" -> squares_x 9, squares_y 7.
void parseSquares(const std::string& text, calibration::BoardLayout& layout) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw core::Error("--squares must be COLUMNSxROWS, e.g. 9x7 (got '" + text + "')");
  layout.squares_x = parseInteger("--squares columns", text.substr(0, x));
  layout.squares_y = parseInteger("--squares rows", text.substr(x + 1));
}

}  // namespace

CLI::Option_group& addBoardOptions(CLI::App& command) {
  CLI::Option_group& group = *command.add_option_group("Board options");
  addText(group, "--board", "TYPE", "charuco (default) or chessboard");
  addText(group, "--squares", "CxR", "Squares across and down (default 9x7)");
  addNumber(group, "--square-mm", "MM", "Side of a square in mm (default 30)");
  addNumber(group, "--marker-mm", "MM", "ChArUco: side of a marker in mm (default 22)");
  addText(group, "--dictionary", "NAME", "ChArUco: ArUco dictionary (default DICT_5X5_100)");
  return group;
}

calibration::BoardLayout boardLayoutFromArguments(const Arguments& args) {
  calibration::BoardLayout layout;
  if (const auto type = args.value("--board")) layout.type = calibration::boardTypeFromName(*type);
  if (const auto squares = args.value("--squares")) parseSquares(*squares, layout);
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

}  // namespace binpick::cli
