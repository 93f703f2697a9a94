// board.json: the board spec and corners, and per pose T_camera_board and the corners' true
// camera and projector pixels.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "binpick/io/error.hpp"
#include "binpick/io/json_fields.hpp"
#include "calibration_truth.hpp"

namespace binpick::sim::detail {
namespace {

using nlohmann::json;

json specJson(const BoardSpec& spec) {
  return {{"type", boardTypeName(spec.type)},
          {"squares_x", spec.squares_x},
          {"squares_y", spec.squares_y},
          {"square_size", spec.square_size},
          {"marker_size", spec.marker_size},
          {"dictionary", spec.dictionary},
          {"margin", spec.margin},
          {"thickness", spec.thickness},
          {"white_albedo", spec.white_albedo},
          {"black_albedo", spec.black_albedo}};
}

json poseJson(const CalibrationTruthPose& pose) {
  json corners = json::array();
  for (const CornerObservation& c : pose.corners) {
    corners.push_back({{"id", c.id},
                       {"camera", {c.camera_pixel.x(), c.camera_pixel.y()}},
                       {"projector", {c.projector_pixel.x(), c.projector_pixel.y()}}});
  }
  return {{"capture", pose.capture},
          {"T_camera_board", poseRows(pose.T_camera_board)},
          {"corners", corners}};
}

}  // namespace

std::string boardTruthPath(const std::string& directory) {
  return (std::filesystem::path(directory) / "truth" / "board.json").string();
}

void writeBoardTruth(const std::string& path, const CalibrationTruth& truth) {
  json corners = json::array();
  for (const BoardCorner& c : truth.corners) {
    corners.push_back({{"id", c.id}, {"point", {c.point.x(), c.point.y(), c.point.z()}}});
  }
  json poses = json::array();
  for (const CalibrationTruthPose& pose : truth.poses) poses.push_back(poseJson(pose));
  const json document = {{"format_version", kBoardTruthVersion},
                         {"units", "m"},
                         {"board", specJson(truth.board)},
                         {"corners", corners},
                         {"poses", poses}};
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    out << document.dump(1) << '\n';
    if (!out) throw Error(path + ": cannot write the board truth file");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(path + ": cannot write the board truth file");
  }
}

}  // namespace binpick::sim::detail
