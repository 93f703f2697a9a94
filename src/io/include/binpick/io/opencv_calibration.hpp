#pragma once
// A rig calibration written by another tool with cv::FileStorage (XML, YAML or JSON), as the
// cv::stereoCalibrate-based projector-camera tools write it: the camera's and the projector's
// matrix and distortion, and R, T from the camera into the projector (x_p = R x_c + T). Each
// tool names its keys its own way; the common names (and misspellings) are tried, and any role
// can be given its key by name. A file without R and T but with each device's pose of the
// calibration board (rotation and translation per view) gets R, T by composing them:
// T_projector_camera = T_projector_board * T_camera_board^-1, averaged over the views.
//
// Units are explicit: tools write the translation in the unit of the board's squares, which the
// file does not record; the result is in metres, as calib.yaml (rig_calibration.hpp) is.
// Stateless: thread-safe.
#include <map>
#include <string>
#include <vector>

#include "binpick/io/rig_calibration.hpp"

namespace binpick::io {

enum class LengthUnit { Millimetres, Metres };
// "mm" | "m"; throws core::Error naming the choices otherwise.
LengthUnit lengthUnitFromName(const std::string& name);

struct OpenCvCalibrationOptions {
  LengthUnit units = LengthUnit::Millimetres;  // of the translation in the file
  // 0: from the file (img_shape, image_size, imageSize, image_width/image_height, ...), else
  // required. Given and in the file too, they must agree: the intrinsics belong to one size.
  int camera_width = 0, camera_height = 0;
  // 0: from the file if it has them (projector_size, proj_shape, ...), else required; the error
  // names --projector, the option that gives them.
  int projector_width = 0, projector_height = 0;
  // Role -> the file's key, overriding the names tried. Roles: openCvCalibrationRoles().
  std::map<std::string, std::string> keys;
  void validate() const;  // throws core::Error naming the field or role
};

// The roles a key can be given for, in the order the reader looks for them: camera_matrix,
// camera_distortion, projector_matrix, projector_distortion, rotation, translation, then the
// board poses (camera_board_rotation, camera_board_translation, projector_board_rotation,
// projector_board_translation) used when the file has no rotation and translation.
const std::vector<std::string>& openCvCalibrationRoles();
// The key names tried for a role, in order; throws core::Error on an unknown role.
const std::vector<std::string>& openCvCalibrationKeyNames(const std::string& role);

// Throws core::Error, one line "PATH: ..." naming the role and the keys tried, on an unreadable
// file, a role not found ("no projector matrix (tried proj_int, projector_matrix, ...; give
// --key projector_matrix=NAME)"), two keys found for one role, a matrix of the wrong shape or with
// non-finite values, a camera matrix with skew, distortion terms the lens model lacks (non-zero
// k4 k5 k6 s1..s4 tauX tauY), a rotation that is not one, a translation implausible for the
// units (a baseline under 1 mm read as millimetres, over 10 m read as metres), or a missing
// image size. The result passes RigCalibration::validate.
RigCalibration readOpenCvCalibration(const std::string& path, const OpenCvCalibrationOptions& options);

}  // namespace binpick::io
