#include "binpick/cell/cell_config.hpp"

#include <filesystem>

#include "binpick/reconstruction/reconstruction_config.hpp"
#include "config_pose.hpp"
#include "config_sections.hpp"

namespace binpick::cell {
namespace {

void validateAll(const CellConfig& config) {
  validateSettings(config.origin, [&] {
    if (config.source.mode == SourceConfig::Mode::Live) {
      config.source.live.camera.validate();
      config.source.live.live.patterns.validate();
      config.source.live.live.sequencer.validate();
      if (config.source.live.trigger == "gpio") config.source.live.gpio.validate();
    }
    PickParams picking = config.picking;
    for (const RecipeConfig& recipe : config.recipes) {
      picking.grasps = recipe.grasps;
      picking.validate();
    }
    config.robot.validate();
    config.limits.validate();
    if (config.artefacts) config.artefacts->validate();
  });
}

}  // namespace

void CycleLimits::validate() const {
  const std::string owner = "limits";
  requireField(capture_timeout_ms > 0, owner, "capture_timeout_ms", "> 0", capture_timeout_ms);
  requireField(processing_timeout_ms > 0, owner, "processing_timeout_ms", "> 0", processing_timeout_ms);
  requireField(max_picks >= 1, owner, "max_picks", ">= 1", max_picks);
  requireField(min_pick_coverage >= 0 && min_pick_coverage <= 1, owner, "min_pick_coverage", "in [0, 1]",
               min_pick_coverage);
  requireField(empty_bin_max_points >= 0, owner, "empty_bin_max_points", ">= 0", empty_bin_max_points);
  requireField(empty_bin_min_height >= 0, owner, "empty_bin_min_height", ">= 0", empty_bin_min_height);
  requireField(avoid_cycles >= 0, owner, "avoid_cycles", ">= 0", avoid_cycles);
}

CellConfig parseCellConfig(const std::string& yaml_text, const std::string& origin,
                           const std::string& base_directory) {
  CellConfig config;
  config.origin = origin;
  const PathResolver resolve{base_directory};
  YamlSection top(parseYaml(yaml_text, origin), "", config.origin);
  if (top.isNull()) throw Error(origin + ": the settings file is empty");
  config.source = readSource(top.child("source"), resolve);
  top.read("calibration", config.calibration);
  config.calibration = resolve(config.calibration);
  YamlSection hand_eye = top.child("hand_eye");
  if (hand_eye.has("T_base_camera")) config.T_base_camera = readPose(hand_eye.child("T_base_camera"));
  else hand_eye.skip("T_base_camera");
  hand_eye.finish();
  top.skip("recipes");
  config.recipes = readRecipes(top.node()["recipes"], config.origin, resolve);
  config.picking = readPicking(top.child("picking"));
  config.robot = readRobot(top.child("robot"));
  config.limits = readLimits(top.child("limits"));
  config.artefacts = readArtefacts(top.child("artefacts"), resolve);
  config.reconstruction = reconstruction::readReconstructionSection(top.child("reconstruction"), config.origin);
  top.finish();
  validateAll(config);
  return config;
}

CellConfig loadCellConfig(const std::string& path) {
  const std::string directory = std::filesystem::absolute(path).parent_path().string();
  return parseCellConfig(readConfigFile(path), path, directory);
}

}  // namespace binpick::cell
