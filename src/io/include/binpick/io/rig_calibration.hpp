#pragma once
// The structured-light rig: a camera and a projector, each with its lens, and where the projector
// sits relative to the camera. Stored as OpenCV FileStorage YAML (calib.yaml); the format is
// documented in docs/capture-format.md. Functions are stateless: thread-safe.
#include <Eigen/Geometry>
#include <string>

#include "binpick/io/lens.hpp"

namespace binpick {

struct RigCalibration {
  LensIntrinsics camera;
  LensIntrinsics projector;
  // Maps camera-frame points into the projector frame: x_p = R x_c + T (OpenCV stereoCalibrate's
  // R, T with the camera first). Metres.
  Eigen::Isometry3d T_projector_camera = Eigen::Isometry3d::Identity();

  // Throws binpick::Error naming the bad field; R must be a rotation (orthonormal, det +1).
  void validate() const;
};

// Throws binpick::Error "PATH: ..." on a missing/unreadable file, a missing key, a matrix of the
// wrong size, a non-finite value or a non-rotation R.
RigCalibration readRigCalibration(const std::string& path);
// Written through a temporary file and a rename: a reader never sees half a file.
void writeRigCalibration(const std::string& path, const RigCalibration& rig);

}  // namespace binpick
