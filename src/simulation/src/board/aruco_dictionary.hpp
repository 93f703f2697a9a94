#pragma once
// OpenCV's predefined ArUco dictionaries by name ("DICT_5X5_100"), so that a board spec can be
// written to and read from text. Internal to binpick::simulation. Pure functions: thread-safe.
#include <string>

namespace binpick::sim::detail {

// The cv::aruco::PREDEFINED_DICTIONARY_NAME value of `name`, or -1 for an unknown name.
int arucoDictionaryId(const std::string& name);
// Markers in the dictionary `id` (a valid id from arucoDictionaryId).
int arucoDictionarySize(int id);
// The known names, comma-separated, for error messages.
std::string arucoDictionaryNames();

}  // namespace binpick::sim::detail
