#pragma once
// The structured-light rig: a camera and a projector, each with its lens, and where the projector
// sits relative to the camera. Stored as OpenCV FileStorage YAML (calib.yaml); the format is
// documented in docs/capture-format.md. A calibration may store how well it fitted beside the rig
// (RigCalibrationQuality, the file's `quality` map); readRigCalibration ignores it.
// Functions are stateless: thread-safe.
#include <Eigen/Geometry>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "binpick/io/lens.hpp"

namespace binpick::io {

struct RigCalibration {
  LensIntrinsics camera;
  LensIntrinsics projector;
  // Maps camera-frame points into the projector frame: x_p = R x_c + T (OpenCV stereoCalibrate's
  // R, T with the camera first). Metres.
  Eigen::Isometry3d T_projector_camera = Eigen::Isometry3d::Identity();

  // Throws core::Error naming the bad field; R must be a rotation (orthonormal, det +1).
  void validate() const;
};

// One view (capture) of a calibration, as the calibration judged it.
struct RigViewQuality {
  std::string name;           // the capture directory
  int camera_corners = 0;     // board corners found in the camera image
  int projector_corners = 0;  // of those, with a projector pixel
  // Reprojection RMS of the view's corners under the rig that judged it: the written rig for
  // used views, the first solve for dropped outliers; NaN for views never calibrated.
  double camera_rms_px = std::numeric_limits<double>::quiet_NaN();
  double projector_rms_px = std::numeric_limits<double>::quiet_NaN();
  bool outlier = false;  // its RMS stood out from the other views'
  bool used = false;     // went into the written calibration
  std::string problem;   // why it was not used; empty when used
};

struct RigCalibrationQuality {
  std::string date;                   // ISO 8601 UTC, when the calibration was computed
  double camera_rms_px = 0.0;         // reprojection RMS of the camera's own calibration
  double projector_rms_px = 0.0;      // of the projector's (as an inverse camera)
  double stereo_rms_px = 0.0;         // of both devices under the final rig
  std::vector<RigViewQuality> views;  // every view offered, used or not, in the order given
  int viewsUsed() const;
};

// Throws core::Error "PATH: ..." on a missing/unreadable file, a missing key, a matrix of the
// wrong size, a non-finite value or a non-rotation R.
RigCalibration readRigCalibration(const std::string& path);
// Written through a temporary file and a rename: a reader never sees half a file.
void writeRigCalibration(const std::string& path, const RigCalibration& rig);
// The same, with the calibration's quality in the file's `quality` map.
void writeRigCalibration(const std::string& path, const RigCalibration& rig, const RigCalibrationQuality& quality);
// The `quality` map of a calibration file; empty when the file has none (written by hand or by
// older versions). Throws core::Error "PATH: ..." on an unreadable file or a malformed map.
std::optional<RigCalibrationQuality> readRigCalibrationQuality(const std::string& path);

}  // namespace binpick::io
