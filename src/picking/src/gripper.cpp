#include "binpick/picking/gripper.hpp"

#include <cmath>

#include "binpick/core/error.hpp"
#include "rigid.hpp"

namespace binpick::picking {
namespace {

const std::string kOwner = "picking.gripper";

}  // namespace

GripperType gripperTypeFromName(const std::string& name) {
  if (name == "suction") return GripperType::Suction;
  if (name == "parallel") return GripperType::Parallel;
  throw core::Error("unknown gripper \"" + name + "\" (use suction or parallel)");
}

std::string gripperTypeName(GripperType type) { return type == GripperType::Suction ? "suction" : "parallel"; }

void GripperParams::validate() const {
  core::requireField(isPositive(cup_diameter), kOwner, "cup_diameter", "> 0", cup_diameter);
  core::requireField(isNonNegative(cup_length), kOwner, "cup_length", ">= 0", cup_length);
  core::requireField(isPositive(seal_tolerance), kOwner, "seal_tolerance", "> 0", seal_tolerance);
  core::requireField(max_lean_deg >= 0.0 && max_lean_deg <= 30.0, kOwner, "max_lean_deg", "in [0, 30]", max_lean_deg);
  core::requireField(nose_angle_deg >= 0.0 && nose_angle_deg <= 60.0, kOwner, "nose_angle_deg", "in [0, 60]",
                     nose_angle_deg);
  core::requireField(isPositive(stroke), kOwner, "stroke", "> 0", stroke);
  core::requireField(isPositive(finger_width), kOwner, "finger_width", "> 0", finger_width);
  core::requireField(isPositive(finger_depth), kOwner, "finger_depth", "> 0", finger_depth);
  core::requireField(isPositive(finger_thickness), kOwner, "finger_thickness", "> 0", finger_thickness);
  core::requireField(isNonNegative(tool_radius), kOwner, "tool_radius", ">= 0", tool_radius);
  core::requireField(isNonNegative(tool_length), kOwner, "tool_length", ">= 0", tool_length);
}

}  // namespace binpick::picking
