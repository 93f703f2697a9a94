#pragma once
// Poses in settings files: {translation: [x, y, z] (metres), rotation: [...], convention: NAME}
// with the rotation in one of the robot orientation conventions (robot_orientation.hpp; default
// quaternion w, x, y, z), so that a pose read off a teach pendant can be pasted as it is.
#include <Eigen/Geometry>

#include "binpick/io/yaml_section.hpp"

namespace binpick::cell {

Eigen::Isometry3d readPose(YamlSection section);

}  // namespace binpick::cell
