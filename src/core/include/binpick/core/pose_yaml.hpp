#pragma once
// Poses in settings files, one form for binpickd's settings, recipes, grasps files and
// hand_eye.yaml:
//   {translation: [x, y, z] (metres), rotation: [...], convention: NAME}
// with the rotation in one of the robot orientation conventions (orientation.hpp; default
// quaternion w, x, y, z), so that a pose read off a teach pendant can be pasted as it is.
#include <Eigen/Geometry>
#include <string>

#include "binpick/core/yaml_section.hpp"

namespace binpick::core {

// Optional: a missing translation is zero and a missing rotation the identity (a bin placed
// square to the base needs only its translation). Required: both must be there (files written
// by a calibration, where a missing field means a damaged file).
enum class PoseFields { Optional, Required };

// Reads the section's keys and finish()es it (so unknown keys are refused); throws core::Error
// naming SECTION.translation or SECTION.rotation when a value is missing (Required), not finite,
// of the wrong count for the convention, or the convention is unknown.
Eigen::Isometry3d readPose(YamlSection section, PoseFields fields = PoseFields::Optional);

// The three lines readPose reads, each started by INDENT: translation (metres), rotation as a
// quaternion with w >= 0, convention. Ten significant digits: below a nanometre and 1e-9 rad.
std::string poseYaml(const Eigen::Isometry3d& pose, const std::string& indent);

// A number as poseYaml writes it: ten significant digits, rounding residue below 1e-15 as 0.
std::string yamlNumber(double value);

}  // namespace binpick::core
