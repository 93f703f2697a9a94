#pragma once
// binpickd's settings and the files they name, for the settings fuzz targets
// (cell_config_fuzz.cpp, grasps_file_fuzz.cpp, hand_eye_file_fuzz.cpp): valid companion files
// written once per process into the scratch directory, so that the fuzzed file is read by the
// real loader (loadCellConfig) with every file it refers to in place.
#include <string>

#include "binpick/cell/cell_config.hpp"
#include "fuzz_support.hpp"

namespace binpick::fuzz {

// A grasps file as `binpick grasps` writes it.
constexpr const char* kGraspsFile = R"(# grasps of the fuzz part
grasps:
  - name: "top"
    translation: [0, 0, 0.01]  # metres
    rotation: [0, 1, 0, 0]  # w x y z
    convention: quaternion
    quality: 0.9
  - name: "side"
    translation: [0.02, 0, 0.005]
    rotation: [90, 0, 0]
    convention: euler_xyz
    quality: 0.5
    width: 0.012
)";

// A hand-eye result file as `binpick calibrate hand-eye` writes it.
constexpr const char* kHandEyeFile = R"(hand_eye:
  T_base_camera:
    translation: [0.6004234699, -0.0006911248167, 0.8999230274]  # metres
    rotation: [0.0002618546121, -0.9999999219, -0.000200288833, 0.0002181495415]  # w x y z
    convention: quaternion
  details:
    setup: eye-to-hand
    method: shah
    date: 2026-01-31T12:00:38.132Z
    views: 8
    residual_rms_mm: 0.1892548455
    residual_rms_deg: 0.06647933417
    T_flange_board: {translation: [0.1, 0, 0.05], rotation: [1, 0, 0, 0], convention: quaternion}
)";

// Settings that name both files; the settings fuzz targets swap one of the three for the input.
constexpr const char* kSettingsFile = R"(source: {mode: replay, replay: {path: replay, loop: true}}
calibration: calib.yaml
hand_eye: {file: hand_eye.yaml}
recipes:
  - name: part
    model: part.ply
    settings: detection.yaml
    symmetry: {order: 2, axis: [0, 0, 1]}
    grasps: part.grasps.yaml
picking:
  bin: {T_base_bin: {translation: [0.6, 0.0, 0.0]}}
robot: {bind_address: 127.0.0.1, port: 50100, orientation: euler_zyx}
)";

// The scratch directory with the three files in it, written on the first call.
inline const std::filesystem::path& cellDirectory() {
  static const std::filesystem::path directory = [] {
    const std::filesystem::path created = scratchDirectory() / "cell";
    std::filesystem::create_directories(created);
    writeBytes(created / "binpickd.yaml", kSettingsFile);
    writeBytes(created / "part.grasps.yaml", kGraspsFile);
    writeBytes(created / "hand_eye.yaml", kHandEyeFile);
    return created;
  }();
  return directory;
}

// What an accepted configuration must hold (cell_config.hpp): at least one recipe, each named
// and with a model, grasp qualities in [0, 1].
inline void checkCellConfig(const cell::CellConfig& config, const std::string& reader, const std::string& input) {
  require(!config.recipes.empty(), reader, "at least one recipe", input);
  for (const cell::RecipeConfig& recipe : config.recipes) {
    require(!recipe.name.empty() && !recipe.model_file.empty(), reader, "recipes have a name and a model", input);
    for (const picking::Grasp& grasp : recipe.grasps) {
      require(grasp.quality >= 0.0 && grasp.quality <= 1.0, reader, "grasp qualities in [0, 1]", input);
    }
  }
}

// Writes the input as `file` of the cell directory, loads the settings, and puts the valid file
// back so that the next input starts from the same companions.
inline void fuzzCellFile(const std::string& file, const char* valid, const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::filesystem::path directory = cellDirectory();
  const std::string path = (directory / file).string();
  writeBytes(path, input);
  const std::string reader = "loadCellConfig(" + file + ")";
  cell::CellConfig config;
  if (readsOrRefuses(reader, path, input, [&] { config = cell::loadCellConfig((directory / "binpickd.yaml").string()); })) {
    checkCellConfig(config, reader, input);
  }
  writeBytes(path, valid);
}

}  // namespace binpick::fuzz
