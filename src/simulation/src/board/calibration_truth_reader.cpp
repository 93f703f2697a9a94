// readCalibrationTruth: board.json back into values, every key required and type-checked.
#include <nlohmann/json.hpp>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/json_fields.hpp"
#include "calibration_truth.hpp"

namespace binpick::simulation {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw core::Error(path + ": " + what); }

json arrayField(const json& object, const char* key, const std::string& path) {
  json value = core::jsonField<json>(object, key, path);
  if (!value.is_array()) fail(path, std::string("key '") + key + "' must be an array");
  return value;
}

template <int N>
Eigen::Matrix<double, N, 1> vectorField(const json& object, const char* key, const std::string& path) {
  const auto values = core::jsonField<std::vector<double>>(object, key, path);
  if (values.size() != N) fail(path, std::string("key '") + key + "' must hold " + std::to_string(N) + " numbers");
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(values.data());
}

BoardSpec specFrom(const json& o, const std::string& path) {
  BoardSpec spec;
  try {
    spec.type = boardTypeFromName(core::jsonField<std::string>(o, "type", path));
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  spec.squares_x = core::jsonField<int>(o, "squares_x", path);
  spec.squares_y = core::jsonField<int>(o, "squares_y", path);
  spec.square_size = core::jsonField<double>(o, "square_size", path);
  spec.marker_size = core::jsonField<double>(o, "marker_size", path);
  spec.dictionary = core::jsonField<std::string>(o, "dictionary", path);
  spec.margin = core::jsonField<double>(o, "margin", path);
  spec.thickness = core::jsonField<double>(o, "thickness", path);
  spec.white_albedo = core::jsonField<double>(o, "white_albedo", path);
  spec.black_albedo = core::jsonField<double>(o, "black_albedo", path);
  try {
    spec.validate();
  } catch (const core::Error& e) {
    fail(path, e.what());
  }
  return spec;
}

CalibrationTruthPose poseFrom(const json& o, const std::string& path) {
  CalibrationTruthPose pose;
  pose.capture = core::jsonField<std::string>(o, "capture", path);
  pose.T_camera_board = core::poseFromRows(core::jsonField<json>(o, "T_camera_board", path), path, "T_camera_board");
  for (const json& c : arrayField(o, "corners", path)) {
    pose.corners.push_back(
        {core::jsonField<int>(c, "id", path), vectorField<2>(c, "camera", path), vectorField<2>(c, "projector", path)});
  }
  return pose;
}

}  // namespace

CalibrationTruth readCalibrationTruth(const std::string& directory) {
  const std::string path = detail::boardTruthPath(directory);
  const json document = core::readJsonFile(path);
  if (core::jsonField<int>(document, "format_version", path) != detail::kBoardTruthVersion) {
    fail(path, "unsupported format_version");
  }
  CalibrationTruth truth;
  truth.board = specFrom(core::jsonField<json>(document, "board", path), path);
  for (const json& c : arrayField(document, "corners", path)) {
    truth.corners.push_back({core::jsonField<int>(c, "id", path), vectorField<3>(c, "point", path)});
  }
  for (const json& p : arrayField(document, "poses", path)) {
    truth.poses.push_back(poseFrom(p, path));
  }
  return truth;
}

}  // namespace binpick::simulation
