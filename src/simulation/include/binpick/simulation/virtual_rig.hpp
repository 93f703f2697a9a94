#pragma once
// The virtual cell's structured-light rig: a 1280x1024 camera with a mildly distorting lens, and a
// 1280x800 projector 0.25 m to its right, turned in so that both optical axes meet at the
// working distance. Pure: thread-safe.
#include "binpick/io/rig_calibration.hpp"

namespace binpick::simulation {

struct VirtualRigParams {
  double working_distance = 0.9;  // metres along the camera axis where the optical axes cross
  double baseline = 0.25;         // metres, projector centre along the camera's +x
  void validate() const;          // throws core::Error naming the field
};

io::RigCalibration makeVirtualRig(const VirtualRigParams& params = {});

}  // namespace binpick::simulation
