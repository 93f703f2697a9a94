#include "binpick/cell/cell_config.hpp"

#include <filesystem>

#include "binpick/core/pose_yaml.hpp"
#include "binpick/reconstruction/reconstruction_config.hpp"
#include "config_sections.hpp"
#include "pick_delivery.hpp"

namespace binpick::cell {
namespace {

void validateAll(const CellConfig& config) {
  core::validateSettings(config.origin, [&] {
    if (config.source.mode == SourceConfig::Mode::Live) {
      config.source.live.camera.validate();
      config.source.live.live.patterns.validate();
      config.source.live.live.sequencer.validate();
      if (config.source.live.trigger == "gpio") config.source.live.gpio.validate();
    }
    picking::PickParams picking = config.picking;
    // A recipe without grasps gets them generated from its model (cell_setup.cpp): the rest of
    // the picking settings are checked with a stand-in grasp.
    for (const RecipeConfig& recipe : config.recipes) {
      picking.grasps = recipe.grasps.empty() ? std::vector<picking::Grasp>{picking::Grasp{}} : recipe.grasps;
      picking.symmetry = recipe.symmetry.value_or(picking::PartSymmetry{});
      picking.validate();
    }
    config.robot.validate("robot");  // the section's name, so that messages name the key in the file
    config.limits.validate();
    checkPickRepliesFit(config.robot.codec, config.limits.max_picks);
    if (config.artefacts) config.artefacts->validate();
    if (config.web) {
      config.web->validate();
      // Both servers on one port of one address: the second could never listen.
      const bool same_address = config.web->bind_address == config.robot.bind_address ||
                                config.web->bind_address == "0.0.0.0" || config.robot.bind_address == "0.0.0.0";
      core::requireField(config.web->port == 0 || config.web->port != config.robot.port || !same_address, "web", "port",
                         "different from robot.port", config.web->port);
    }
  });
}

// The result file of `binpick calibrate hand-eye` (binpick/calibration/hand_eye_file.hpp): its
// hand_eye.T_base_camera; `details` is the calibration's record. An eye-in-hand result holds
// T_flange_camera instead, which a fixed-camera cell cannot use.
Eigen::Isometry3d readHandEyeFile(const std::string& path) {
  core::YamlSection top(core::parseYaml(core::readConfigFile(path), path), "", path);
  core::YamlSection section = top.child("hand_eye");
  top.finish();
  if (!section.has("T_base_camera")) {
    section.fail("T_base_camera", section.has("T_flange_camera")
                                      ? "is missing: the file is an eye-in-hand calibration "
                                        "(T_flange_camera); binpickd needs the fixed camera's pose"
                                      : "is missing");
  }
  const Eigen::Isometry3d pose = core::readPose(section.child("T_base_camera"));
  section.skip("details");
  section.finish();
  return pose;
}

// hand_eye: {T_base_camera: POSE} written in place, or {file: PATH} naming a result file.
std::optional<Eigen::Isometry3d> readHandEye(core::YamlSection section, const PathResolver& resolve,
                                             const std::string& origin) {
  std::string file;
  section.read("file", file);
  section.skip("details");  // a result file's section pasted in keeps its record
  const bool in_place = section.has("T_base_camera");
  if (in_place && !file.empty()) {
    section.fail("file", "and hand_eye.T_base_camera are both given: keep one");
  }
  std::optional<Eigen::Isometry3d> pose;
  if (in_place)
    pose = core::readPose(section.child("T_base_camera"));
  else
    section.skip("T_base_camera");
  section.finish();
  if (file.empty()) return pose;
  try {
    return readHandEyeFile(resolve(file));
  } catch (const core::Error& e) {
    throw core::Error(origin + ": hand_eye.file: " + e.what());
  }
}

}  // namespace

void CycleLimits::validate() const {
  const std::string owner = "limits";
  core::requireField(capture_timeout_ms > 0, owner, "capture_timeout_ms", "> 0", capture_timeout_ms);
  core::requireField(processing_timeout_ms > 0, owner, "processing_timeout_ms", "> 0", processing_timeout_ms);
  core::requireField(max_picks >= 1, owner, "max_picks", ">= 1", max_picks);
  core::requireField(min_pick_coverage >= 0 && min_pick_coverage <= 1, owner, "min_pick_coverage", "in [0, 1]",
                     min_pick_coverage);
  core::requireField(empty_bin_max_points >= 0, owner, "empty_bin_max_points", ">= 0", empty_bin_max_points);
  core::requireField(empty_bin_min_height >= 0, owner, "empty_bin_min_height", ">= 0", empty_bin_min_height);
  core::requireField(avoid_cycles >= 0, owner, "avoid_cycles", ">= 0", avoid_cycles);
}

CellConfig parseCellConfig(const std::string& yaml_text, const std::string& origin, const std::string& base_directory) {
  CellConfig config;
  config.origin = origin;
  const PathResolver resolve{base_directory};
  core::YamlSection top(core::parseYaml(yaml_text, origin), "", config.origin);
  if (top.isNull()) throw core::Error(origin + ": the settings file is empty");
  config.source = readSource(top.child("source"), resolve);
  top.read("calibration", config.calibration);
  config.calibration = resolve(config.calibration);
  config.T_base_camera = readHandEye(top.child("hand_eye"), resolve, config.origin);
  top.skip("recipes");
  config.recipes = readRecipes(top.node()["recipes"], config.origin, resolve);
  config.picking = readPicking(top.child("picking"));
  config.robot = readRobot(top.child("robot"));
  config.limits = readLimits(top.child("limits"));
  config.artefacts = readArtefacts(top.child("artefacts"), resolve);
  config.web = readWebView(top.child("web"));
  config.reconstruction = reconstruction::readReconstructionSection(top.child("reconstruction"), config.origin);
  top.finish();
  validateAll(config);
  return config;
}

CellConfig loadCellConfig(const std::string& path) {
  const std::string directory = std::filesystem::absolute(path).parent_path().string();
  return parseCellConfig(core::readConfigFile(path), path, directory);
}

}  // namespace binpick::cell
