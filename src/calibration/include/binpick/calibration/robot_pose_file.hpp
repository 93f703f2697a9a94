#pragma once
// poses.txt of a hand-eye views directory: one robot pose per view, as the teach pendant shows
// it (docs/hand-eye.md):
//   # comment lines and blank lines are ignored
//   orientation: euler_zyx            (required first; any robot protocol orientation name)
//   view_00 612.5 -40.2 310.0 180 0 90
//   VIEW x y z v1 v2 v3 [v4]
// VIEW matches [A-Za-z0-9_.-]+; x y z are millimetres; then orientationValueCount values in
// that convention (robot_orientation.hpp). Each pose is T_base_flange: the flange (tool0, no
// TCP offset) in the robot base frame. Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/core/orientation.hpp"

namespace binpick::calibration {

struct RobotPose {
  std::string view;
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity();  // metres
  int line = 0;  // where it was read, for messages; 0 when not from a file
};

struct RobotPoseFile {
  core::Orientation orientation = core::Orientation::EulerZYX;
  std::vector<RobotPose> poses;  // file order
};

// Throws core::Error "ORIGIN:LINE: ..." naming the view where there is one: a missing or
// unknown orientation line, a bad view name, a wrong value count, a value that is not a finite
// number, a zero quaternion or one whose norm is off 1 by more than 1%, a rotation vector
// longer than pi, a view listed twice.
RobotPoseFile parseRobotPoses(const std::string& text, const std::string& origin);
RobotPoseFile readRobotPoseFile(const std::string& path);  // also throws "PATH: cannot read"

// Millimetres with 4 decimals and rotations with 9: far below any robot's resolution.
std::string formatRobotPoses(const RobotPoseFile& file);
// Written through a temporary file and a rename: a reader never sees half a file.
void writeRobotPoseFile(const std::string& path, const RobotPoseFile& file);

}  // namespace binpick::calibration
