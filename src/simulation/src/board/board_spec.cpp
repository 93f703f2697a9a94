// BoardSpec::validate and the board type names.
#include <cmath>
#include <sstream>

#include "aruco_dictionary.hpp"
#include "binpick/io/error.hpp"
#include "binpick/simulation/calibration_board.hpp"

namespace binpick::sim {
namespace {

template <typename T>
void require(bool ok, const char* field, const char* rule, const T& value) {
  requireField(ok, "BoardSpec", field, rule, value);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

void validateMarkers(const BoardSpec& spec) {
  require(positive(spec.marker_size) && spec.marker_size < spec.square_size, "marker_size",
          "positive and smaller than square_size", spec.marker_size);
  const int id = detail::arucoDictionaryId(spec.dictionary);
  require(id >= 0, "dictionary", ("one of " + detail::arucoDictionaryNames()).c_str(),
          spec.dictionary);
  // A ChArUco board puts one marker in each white square: half of them, rounded down.
  const int markers = spec.squares_x * spec.squares_y / 2;
  const int available = detail::arucoDictionarySize(id);
  if (markers > available) {
    std::ostringstream message;
    message << "BoardSpec.dictionary " << spec.dictionary << " holds " << available
            << " markers; a " << spec.squares_x << "x" << spec.squares_y << " board needs "
            << markers;
    throw Error(message.str());
  }
}

}  // namespace

std::string boardTypeName(BoardType type) {
  return type == BoardType::Chessboard ? "chessboard" : "charuco";
}

BoardType boardTypeFromName(const std::string& name) {
  if (name == "chessboard") return BoardType::Chessboard;
  if (name == "charuco") return BoardType::Charuco;
  throw Error("board type must be 'chessboard' or 'charuco' (got '" + name + "')");
}

void BoardSpec::validate() const {
  require(type == BoardType::Chessboard || type == BoardType::Charuco, "type",
          "chessboard or charuco", static_cast<int>(type));
  // Fewer squares leave a single row of inner corners, which OpenCV's detectors reject.
  require(squares_x >= 3, "squares_x", ">= 3", squares_x);
  require(squares_y >= 3, "squares_y", ">= 3", squares_y);
  require(positive(square_size), "square_size", "positive", square_size);
  require(std::isfinite(margin) && margin >= 0.0, "margin", ">= 0", margin);
  require(positive(thickness), "thickness", "positive", thickness);
  require(std::isfinite(white_albedo) && white_albedo > 0.0 && white_albedo <= 1.0, "white_albedo",
          "in (0, 1]", white_albedo);
  require(std::isfinite(black_albedo) && black_albedo >= 0.0 && black_albedo < white_albedo,
          "black_albedo", "in [0, white_albedo)", black_albedo);
  if (type == BoardType::Charuco) validateMarkers(*this);
}

}  // namespace binpick::sim
