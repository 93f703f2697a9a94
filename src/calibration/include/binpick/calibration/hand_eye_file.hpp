#pragma once
// hand_eye.yaml: a hand-eye calibration in binpickd's settings format, so that binpickd reads it
// with `hand_eye: {file: hand_eye.yaml}` (or its section is pasted into the settings):
//   hand_eye:
//     T_base_camera:                  (T_flange_camera for eye-in-hand)
//       translation: [x, y, z]        metres
//       rotation: [w, x, y, z]        unit quaternion, w >= 0
//       convention: quaternion
//     details:                        the calibration's record; binpickd skips it
//       setup: eye-to-hand
//       method: shah
//       date: 2026-01-31T12:00:00.000Z
//       views: 12
//       residual_rms_mm: 0.31
//       residual_rms_deg: 0.021
//       T_flange_board: {translation: [...], rotation: [...], convention: quaternion}
// Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <string>

#include "binpick/calibration/hand_eye.hpp"

namespace binpick::calibration {

struct HandEyeFile {
  HandEyeSetup setup = HandEyeSetup::EyeToHand;
  Eigen::Isometry3d T_mount_camera = Eigen::Isometry3d::Identity();  // cameraTransformName
  Eigen::Isometry3d T_mount_board = Eigen::Isometry3d::Identity();   // boardTransformName
  std::string method;  // handEyeMethodDescription, or what else made it ("truth" in the virtual cell)
  std::string date;    // ISO 8601 UTC
  int views = 0;
  double rms_mm = 0.0;
  double rms_deg = 0.0;
};

// The file for a solved calibration, dated now. Throws core::Error when the result failed
// (!result.ok()): a bad calibration is never written.
HandEyeFile handEyeFileOf(const HandEyeResult& result);

// Written through a temporary file and a rename. Throws core::Error when it cannot be.
void writeHandEyeFile(const std::string& path, const HandEyeFile& file);
// Throws core::Error "PATH: key what was wrong" on a missing file, bad YAML, a missing,
// unknown or mistyped key, or a camera transform that does not match the setup.
HandEyeFile readHandEyeFile(const std::string& path);

}  // namespace binpick::calibration
