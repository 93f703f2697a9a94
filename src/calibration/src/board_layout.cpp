// BoardLayout: validation, corner positions, and the names of board types and dictionaries.
#include "binpick/calibration/board_layout.hpp"

#include <cmath>
#include <opencv2/aruco/dictionary.hpp>
#include <sstream>
#include <utility>

#include "binpick/core/error.hpp"

namespace binpick::calibration {
namespace {

namespace aruco = cv::aruco;

const std::pair<const char*, aruco::PREDEFINED_DICTIONARY_NAME> kDictionaries[] = {
    {"DICT_4X4_50", aruco::DICT_4X4_50},
    {"DICT_4X4_100", aruco::DICT_4X4_100},
    {"DICT_4X4_250", aruco::DICT_4X4_250},
    {"DICT_4X4_1000", aruco::DICT_4X4_1000},
    {"DICT_5X5_50", aruco::DICT_5X5_50},
    {"DICT_5X5_100", aruco::DICT_5X5_100},
    {"DICT_5X5_250", aruco::DICT_5X5_250},
    {"DICT_5X5_1000", aruco::DICT_5X5_1000},
    {"DICT_6X6_50", aruco::DICT_6X6_50},
    {"DICT_6X6_100", aruco::DICT_6X6_100},
    {"DICT_6X6_250", aruco::DICT_6X6_250},
    {"DICT_6X6_1000", aruco::DICT_6X6_1000},
    {"DICT_7X7_50", aruco::DICT_7X7_50},
    {"DICT_7X7_100", aruco::DICT_7X7_100},
    {"DICT_7X7_250", aruco::DICT_7X7_250},
    {"DICT_7X7_1000", aruco::DICT_7X7_1000},
    {"DICT_ARUCO_ORIGINAL", aruco::DICT_ARUCO_ORIGINAL},
    {"DICT_APRILTAG_16h5", aruco::DICT_APRILTAG_16h5},
    {"DICT_APRILTAG_25h9", aruco::DICT_APRILTAG_25h9},
    {"DICT_APRILTAG_36h10", aruco::DICT_APRILTAG_36h10},
    {"DICT_APRILTAG_36h11", aruco::DICT_APRILTAG_36h11},
};

template <typename T>
void require(bool ok, const char* field, const char* rule, const T& value) {
  core::requireField(ok, "BoardLayout", field, rule, value);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

void validateMarkers(const BoardLayout& layout) {
  require(positive(layout.marker_size) && layout.marker_size < layout.square_size, "marker_size",
          "positive and smaller than square_size", layout.marker_size);
  const int id = arucoDictionaryId(layout.dictionary);
  require(id >= 0, "dictionary", ("one of " + arucoDictionaryNames()).c_str(), layout.dictionary);
  // A ChArUco board puts one marker in each white square: half of them, rounded down.
  const int markers = layout.squares_x * layout.squares_y / 2;
  const int available = arucoDictionarySize(id);
  if (markers > available) {
    std::ostringstream message;
    message << "BoardLayout.dictionary " << layout.dictionary << " holds " << available << " markers; a "
            << layout.squares_x << "x" << layout.squares_y << " board needs " << markers;
    throw core::Error(message.str());
  }
}

}  // namespace

std::string boardTypeName(BoardType type) { return type == BoardType::Chessboard ? "chessboard" : "charuco"; }

BoardType boardTypeFromName(const std::string& name) {
  if (name == "chessboard") return BoardType::Chessboard;
  if (name == "charuco") return BoardType::Charuco;
  throw core::Error("board type must be 'chessboard' or 'charuco' (got '" + name + "')");
}

int arucoDictionaryId(const std::string& name) {
  for (const auto& [known, id] : kDictionaries) {
    if (name == known) return static_cast<int>(id);
  }
  return -1;
}

int arucoDictionarySize(int id) { return aruco::getPredefinedDictionary(id)->bytesList.rows; }

std::string arucoDictionaryNames() {
  std::string names;
  for (const auto& entry : kDictionaries) {
    if (!names.empty()) names += ", ";
    names += entry.first;
  }
  return names;
}

void BoardLayout::validate() const {
  require(type == BoardType::Chessboard || type == BoardType::Charuco, "type", "chessboard or charuco",
          static_cast<int>(type));
  // Fewer squares leave a single row of inner corners, which OpenCV's detectors reject.
  require(squares_x >= 3, "squares_x", ">= 3", squares_x);
  require(squares_y >= 3, "squares_y", ">= 3", squares_y);
  require(positive(square_size), "square_size", "positive", square_size);
  if (type == BoardType::Charuco) validateMarkers(*this);
}

Eigen::Vector3d BoardLayout::cornerPoint(int id) const {
  if (id < 0 || id >= cornerCount()) {
    throw core::Error("board corner id " + std::to_string(id) + " is outside 0.." + std::to_string(cornerCount() - 1));
  }
  const int columns = squares_x - 1;
  const int row = id / columns, column = id % columns;
  // ChArUco counts from the outer corner of the board, the chessboard from its first inner one.
  const int offset = type == BoardType::Charuco ? 1 : 0;
  return {(column + offset) * square_size, (row + offset) * square_size, 0.0};
}

}  // namespace binpick::calibration
