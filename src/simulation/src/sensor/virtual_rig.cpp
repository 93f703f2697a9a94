#include "binpick/simulation/virtual_rig.hpp"

#include <cmath>
#include <sstream>

#include "binpick/core/error.hpp"

namespace binpick::simulation {
namespace {

// A 1.3 MP machine-vision camera whose lens frames 0.72 x 0.58 m at 0.9 m, with a little barrel
// distortion and an off-centre principal point, as real ones have.
io::LensIntrinsics cameraLens() {
  io::LensIntrinsics lens;
  lens.width = 1280;
  lens.height = 1024;
  lens.fx = lens.fy = 1600.0;
  lens.cx = 641.3;
  lens.cy = 509.8;
  lens.distortion = {-0.08, 0.12, 0.0004, -0.0003, 0.0};
  return lens;
}

// A DLP light engine: it frames a 0.74 x 0.46 m field at 0.9 m; its distortion is small.
io::LensIntrinsics projectorLens() {
  io::LensIntrinsics lens;
  lens.width = 1280;
  lens.height = 800;
  lens.fx = lens.fy = 1560.0;
  lens.cx = 639.5;
  lens.cy = 399.5;
  lens.distortion = {0.02, -0.01, 0.0, 0.0, 0.0};
  return lens;
}

}  // namespace

void VirtualRigParams::validate() const {
  if (!std::isfinite(working_distance) || working_distance <= 0.0) {
    std::ostringstream m;
    m << "VirtualRigParams.working_distance must be positive (got " << working_distance << ")";
    throw core::Error(m.str());
  }
  if (!std::isfinite(baseline) || baseline <= 0.0) {
    std::ostringstream m;
    m << "VirtualRigParams.baseline must be positive (got " << baseline << ")";
    throw core::Error(m.str());
  }
}

io::RigCalibration makeVirtualRig(const VirtualRigParams& params) {
  params.validate();
  io::RigCalibration rig;
  rig.camera = cameraLens();
  rig.projector = projectorLens();
  // The projector sits at (baseline, 0, 0) in the camera frame and is turned about the camera's
  // y axis so that its optical axis passes through (0, 0, working_distance).
  const double toe_in = std::atan2(params.baseline, params.working_distance);
  Eigen::Isometry3d T_camera_projector = Eigen::Isometry3d::Identity();
  T_camera_projector.linear() = Eigen::AngleAxisd(-toe_in, Eigen::Vector3d::UnitY()).matrix();
  T_camera_projector.translation() = Eigen::Vector3d(params.baseline, 0.0, 0.0);
  rig.T_projector_camera = T_camera_projector.inverse();
  return rig;
}

}  // namespace binpick::simulation
