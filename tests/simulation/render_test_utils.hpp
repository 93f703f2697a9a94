#pragma once
// Scenes and rigs for the ray caster and sensor geometry tests: boxes with analytic faces, and
// small cameras and projectors (quarter resolution or less keeps the tests fast).
#include <Eigen/Geometry>
#include <cmath>

#include "binpick/io/point_cloud.hpp"
#include "binpick/io/rig_calibration.hpp"

namespace binpick::simulation::test {

// Axis-aligned box centred on the origin of its frame, outward winding, 12 triangles.
inline io::TriangleMesh boxMesh(const Eigen::Vector3d& half) {
  io::TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back(static_cast<float>((i & 1) ? half.x() : -half.x()),
                               static_cast<float>((i & 2) ? half.y() : -half.y()),
                               static_cast<float>((i & 4) ? half.z() : -half.z()));
  }
  // Each face as a quad, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.emplace_back(q[0], q[1], q[2]);
    mesh.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return mesh;
}

inline Eigen::Isometry3d pose(const Eigen::Vector3d& translation,
                              const Eigen::AngleAxisd& rotation = Eigen::AngleAxisd::Identity()) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation.matrix();
  T.translation() = translation;
  return T;
}

inline io::LensIntrinsics pinholeLens(int width, int height, double f) {
  io::LensIntrinsics lens;
  lens.width = width;
  lens.height = height;
  lens.fx = lens.fy = f;
  lens.cx = 0.5 * (width - 1);
  lens.cy = 0.5 * (height - 1);
  return lens;
}

// The projector `baseline` metres along the camera's +x, turned about y so that its axis crosses
// the camera's at `working_distance`.
inline io::RigCalibration toedInRig(const io::LensIntrinsics& camera, const io::LensIntrinsics& projector,
                                    double baseline = 0.25, double working_distance = 0.9) {
  io::RigCalibration rig;
  rig.camera = camera;
  rig.projector = projector;
  Eigen::Isometry3d T_camera_projector =
      pose(Eigen::Vector3d(baseline, 0.0, 0.0),
           Eigen::AngleAxisd(-std::atan2(baseline, working_distance), Eigen::Vector3d::UnitY()));
  rig.T_projector_camera = T_camera_projector.inverse();
  return rig;
}

// Distortion-free quarter-resolution rig (camera 320 x 256, projector 320 x 200).
inline io::RigCalibration simpleRig() { return toedInRig(pinholeLens(320, 256, 400.0), pinholeLens(320, 200, 390.0)); }

// The same with lenses distorting like real ones (barrel camera, slight pincushion projector).
inline io::RigCalibration distortingRig() {
  io::RigCalibration rig = simpleRig();
  rig.camera.cx = 160.3;
  rig.camera.cy = 127.1;
  rig.camera.distortion = {-0.08, 0.12, 0.0004, -0.0003, 0.0};
  rig.projector.distortion = {0.02, -0.01, 0.0, 0.0, 0.0};
  return rig;
}

// The projector centre in the camera frame.
inline Eigen::Vector3d projectorCentre(const io::RigCalibration& rig) {
  return rig.T_projector_camera.inverse().translation();
}

}  // namespace binpick::simulation::test
