// hand_eye.yaml: writing by hand (a fixed, commented layout) and reading back with YamlSection.
#include "binpick/calibration/hand_eye_file.hpp"

#include <cmath>
#include <cstdio>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "binpick/core/yaml_section.hpp"
#include "binpick/io/capture.hpp"

namespace binpick::calibration {

HandEyeFile handEyeFileOf(const HandEyeResult& result) {
  if (!result.ok()) throw core::Error("hand-eye: not writing a failed calibration: " + result.failure);
  HandEyeFile file;
  file.setup = result.setup;
  file.T_mount_camera = result.T_mount_camera;
  file.T_mount_board = result.T_mount_board;
  file.method = handEyeMethodDescription(result);
  file.date = io::utcTimestamp();
  file.views = static_cast<int>(result.residuals.size() - result.dropped.size());
  file.rms_mm = result.rms_mm;
  file.rms_deg = result.rms_deg;
  return file;
}

void writeHandEyeFile(const std::string& path, const HandEyeFile& file) {
  std::string text =
      "# Hand-eye calibration (binpick calibrate hand-eye, docs/hand-eye.md). binpickd reads it\n"
      "# with `hand_eye: {file: PATH}`; `details` is the calibration's record, not a setting.\n"
      "hand_eye:\n  " +
      cameraTransformName(file.setup) + ":\n" + core::poseYaml(file.T_mount_camera, "    ") + "  details:\n" +
      "    setup: " + handEyeSetupName(file.setup) + "\n" + "    method: " + file.method + "\n" +
      "    date: " + file.date + "\n" + "    views: " + std::to_string(file.views) + "\n" +
      "    residual_rms_mm: " + core::yamlNumber(file.rms_mm) + "\n" +
      "    residual_rms_deg: " + core::yamlNumber(file.rms_deg) + "\n" + "    " + boardTransformName(file.setup) +
      ":\n" + core::poseYaml(file.T_mount_board, "      ");
  core::writeFileAtomically(path, text, core::ParentDirectory::Create);
}

HandEyeFile readHandEyeFile(const std::string& path) {
  core::YamlSection top(core::parseYaml(core::readConfigFile(path), path), "", path);
  core::YamlSection section = top.child("hand_eye");
  core::YamlSection details = section.child("details");
  top.finish();
  HandEyeFile file;
  std::string setup;
  details.read("setup", setup);
  try {
    file.setup = handEyeSetupFromName(setup);
  } catch (const core::Error& e) {
    details.fail("setup", e.what());
  }
  const std::string camera = cameraTransformName(file.setup);
  if (!section.has(camera.c_str())) section.fail(camera, "is missing (setup " + setup + ")");
  file.T_mount_camera = core::readPose(section.child(camera.c_str()), core::PoseFields::Required);
  section.finish();
  file.T_mount_board =
      core::readPose(details.child(boardTransformName(file.setup).c_str()), core::PoseFields::Required);
  details.read("method", file.method);
  details.read("date", file.date);
  details.read("views", file.views);
  details.read("residual_rms_mm", file.rms_mm);
  details.read("residual_rms_deg", file.rms_deg);
  details.finish();
  return file;
}

}  // namespace binpick::calibration
