// hand_eye.yaml: writing by hand (a fixed, commented layout) and reading back with YamlSection.
#include "binpick/calibration/hand_eye_file.hpp"

#include <cmath>
#include <cstdio>

#include "binpick/io/capture.hpp"
#include "binpick/io/error.hpp"
#include "binpick/io/robot_orientation.hpp"
#include "binpick/io/yaml_section.hpp"
#include "hand_eye_text_file.hpp"

namespace binpick::calibration {
namespace {

std::string number(double value) {
  if (std::abs(value) < 1e-15) value = 0.0;  // rounding residue, e.g. cos(pi/2) = 6e-17
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

std::string list(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + number(values[i]);
  return text + "]";
}

// {translation, rotation, convention} as binpickd's settings read poses (metres, quaternion).
std::string poseLines(const std::string& indent, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d& t = T.translation();
  return indent + "translation: " + list({t.x(), t.y(), t.z()}) + "  # metres\n" + indent +
         "rotation: " + list(robot::orientationValues(T.linear(), robot::Orientation::Quaternion)) +
         "  # w x y z\n" + indent + "convention: quaternion\n";
}

Eigen::Isometry3d readPose(YamlSection section) {
  Eigen::Vector3d translation = Eigen::Vector3d::Constant(std::nan(""));
  std::string convention;
  std::vector<double> values;
  section.readVector3("translation", translation);
  section.read("rotation", values);
  section.read("convention", convention);
  section.finish();
  if (!translation.allFinite()) section.fail("translation", "needs three finite numbers");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = translation;
  try {
    pose.linear() = robot::rotationFromValues(values, robot::orientationFromName(convention));
  } catch (const Error& e) {
    section.fail("rotation", e.what());
  }
  return pose;
}

}  // namespace

HandEyeFile handEyeFileOf(const HandEyeResult& result) {
  if (!result.ok()) throw Error("hand-eye: not writing a failed calibration: " + result.failure);
  HandEyeFile file;
  file.setup = result.setup;
  file.T_mount_camera = result.T_mount_camera;
  file.T_mount_board = result.T_mount_board;
  file.method = handEyeMethodName(result.method);
  file.date = utcTimestamp();
  file.views = static_cast<int>(result.residuals.size());
  file.rms_mm = result.rms_mm;
  file.rms_deg = result.rms_deg;
  return file;
}

void writeHandEyeFile(const std::string& path, const HandEyeFile& file) {
  std::string text =
      "# Hand-eye calibration (binpick calibrate hand-eye, docs/hand-eye.md). binpickd reads it\n"
      "# with `hand_eye: {file: PATH}`; `details` is the calibration's record, not a setting.\n"
      "hand_eye:\n  " + cameraTransformName(file.setup) + ":\n" +
      poseLines("    ", file.T_mount_camera) + "  details:\n" +
      "    setup: " + handEyeSetupName(file.setup) + "\n" +
      "    method: " + file.method + "\n" +
      "    date: " + file.date + "\n" +
      "    views: " + std::to_string(file.views) + "\n" +
      "    residual_rms_mm: " + number(file.rms_mm) + "\n" +
      "    residual_rms_deg: " + number(file.rms_deg) + "\n" +
      "    " + boardTransformName(file.setup) + ":\n" + poseLines("      ", file.T_mount_board);
  detail::writeTextFileAtomically(path, text);
}

HandEyeFile readHandEyeFile(const std::string& path) {
  YamlSection top(parseYaml(readConfigFile(path), path), "", path);
  YamlSection section = top.child("hand_eye");
  YamlSection details = section.child("details");
  top.finish();
  HandEyeFile file;
  std::string setup;
  details.read("setup", setup);
  try {
    file.setup = handEyeSetupFromName(setup);
  } catch (const Error& e) {
    details.fail("setup", e.what());
  }
  const std::string camera = cameraTransformName(file.setup);
  if (!section.has(camera.c_str())) section.fail(camera, "is missing (setup " + setup + ")");
  file.T_mount_camera = readPose(section.child(camera.c_str()));
  section.finish();
  file.T_mount_board = readPose(details.child(boardTransformName(file.setup).c_str()));
  details.read("method", file.method);
  details.read("date", file.date);
  details.read("views", file.views);
  details.read("residual_rms_mm", file.rms_mm);
  details.read("residual_rms_deg", file.rms_deg);
  details.finish();
  return file;
}

}  // namespace binpick::calibration
