// readCalibrationTruth: board.json back into values, every key required and type-checked.
#include <fstream>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <vector>

#include "binpick/io/error.hpp"
#include "calibration_truth.hpp"

namespace binpick::sim {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

// The value at `key` as a T; a missing key or a wrong type names the key.
template <typename T>
T field(const json& object, const char* key, const std::string& path) {
  if (!object.is_object()) fail(path, std::string("expected an object holding '") + key + "'");
  const auto it = object.find(key);
  if (it == object.end()) fail(path, std::string("missing key '") + key + "'");
  const bool number_ok = !std::is_arithmetic_v<T> || it->is_number();
  const bool integer_ok = !std::is_integral_v<T> || it->is_number_integer();
  if (number_ok && integer_ok) {
    try {
      return it->get<T>();
    } catch (const json::exception&) {
    }
  }
  fail(path, std::string("key '") + key + "' has the wrong type");
}

json arrayField(const json& object, const char* key, const std::string& path) {
  json value = field<json>(object, key, path);
  if (!value.is_array()) fail(path, std::string("key '") + key + "' must be an array");
  return value;
}

template <int N>
Eigen::Matrix<double, N, 1> vectorField(const json& object, const char* key,
                                        const std::string& path) {
  const auto values = field<std::vector<double>>(object, key, path);
  if (values.size() != N)
    fail(path, std::string("key '") + key + "' must hold " + std::to_string(N) + " numbers");
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(values.data());
}

BoardSpec specFrom(const json& o, const std::string& path) {
  BoardSpec spec;
  try {
    spec.type = boardTypeFromName(field<std::string>(o, "type", path));
  } catch (const Error& e) {
    fail(path, e.what());
  }
  spec.squares_x = field<int>(o, "squares_x", path);
  spec.squares_y = field<int>(o, "squares_y", path);
  spec.square_size = field<double>(o, "square_size", path);
  spec.marker_size = field<double>(o, "marker_size", path);
  spec.dictionary = field<std::string>(o, "dictionary", path);
  spec.margin = field<double>(o, "margin", path);
  spec.thickness = field<double>(o, "thickness", path);
  spec.white_albedo = field<double>(o, "white_albedo", path);
  spec.black_albedo = field<double>(o, "black_albedo", path);
  try {
    spec.validate();
  } catch (const Error& e) {
    fail(path, e.what());
  }
  return spec;
}

CalibrationTruthPose poseFrom(const json& o, const std::string& path) {
  CalibrationTruthPose pose;
  pose.capture = field<std::string>(o, "capture", path);
  const auto rows = field<std::vector<std::vector<double>>>(o, "T_camera_board", path);
  if (rows.size() != 4) fail(path, "'T_camera_board' must have 4 rows");
  for (int r = 0; r < 4; ++r) {
    if (rows[r].size() != 4) fail(path, "'T_camera_board' rows must hold 4 numbers");
    for (int c = 0; c < 4; ++c) pose.T_camera_board.matrix()(r, c) = rows[r][c];
  }
  for (const json& c : arrayField(o, "corners", path)) {
    pose.corners.push_back({field<int>(c, "id", path), vectorField<2>(c, "camera", path),
                            vectorField<2>(c, "projector", path)});
  }
  return pose;
}

}  // namespace

CalibrationTruth readCalibrationTruth(const std::string& directory) {
  const std::string path = detail::boardTruthPath(directory);
  std::ifstream in(path);
  if (!in) fail(path, "cannot open the board truth file");
  json document;
  try {
    document = json::parse(in);
  } catch (const json::exception& e) {
    fail(path, std::string("malformed JSON: ") + e.what());
  }
  if (field<int>(document, "format_version", path) != detail::kBoardTruthVersion) {
    fail(path, "unsupported format_version");
  }
  CalibrationTruth truth;
  truth.board = specFrom(field<json>(document, "board", path), path);
  for (const json& c : arrayField(document, "corners", path)) {
    truth.corners.push_back({field<int>(c, "id", path), vectorField<3>(c, "point", path)});
  }
  for (const json& p : arrayField(document, "poses", path)) {
    truth.poses.push_back(poseFrom(p, path));
  }
  return truth;
}

}  // namespace binpick::sim
