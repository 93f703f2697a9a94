// Names of OpenCV's predefined ArUco dictionaries, as its enum spells them.
#include "aruco_dictionary.hpp"

#include <opencv2/aruco/dictionary.hpp>
#include <utility>

namespace binpick::sim::detail {
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

}  // namespace

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

}  // namespace binpick::sim::detail
