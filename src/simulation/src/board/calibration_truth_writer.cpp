// board.json: the board spec and corners, and per pose T_camera_board and the corners' true
// camera and projector pixels.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/core/json_fields.hpp"
#include "calibration_truth.hpp"

namespace binpick::simulation::detail {
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
  return {{"capture", pose.capture}, {"T_camera_board", core::poseRows(pose.T_camera_board)}, {"corners", corners}};
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
  core::writeFileAtomically(path, document.dump(1) + "\n");
}

}  // namespace binpick::simulation::detail
