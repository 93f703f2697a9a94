#include "binpick/core/pose_yaml.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/orientation.hpp"

namespace binpick::core {

namespace {

std::string list(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + yamlNumber(values[i]);
  return text + "]";
}

}  // namespace

std::string yamlNumber(double value) {
  if (std::abs(value) < 1e-15) value = 0.0;  // rounding residue, e.g. cos(pi/2) = 6e-17
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

Eigen::Isometry3d readPose(YamlSection section, PoseFields fields) {
  if (section.isNull()) section.fail("", "needs translation and rotation");
  if (fields == PoseFields::Required) {
    if (!section.has("translation")) section.fail("translation", "is missing");
    if (!section.has("rotation")) section.fail("rotation", "is missing");
  }
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  section.readVector3("translation", translation);
  std::string convention_name = "quaternion";
  section.read("convention", convention_name);
  std::vector<double> values;
  section.read("rotation", values);
  section.finish();

  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (!translation.allFinite()) section.fail("translation", "must be finite");
  pose.translation() = translation;
  if (values.empty() && fields == PoseFields::Optional) return pose;
  try {
    pose.linear() = rotationFromValues(values, orientationFromName(convention_name));
  } catch (const Error& e) {
    section.fail("rotation", e.what());
  }
  return pose;
}

std::string poseYaml(const Eigen::Isometry3d& pose, const std::string& indent) {
  const Eigen::Vector3d& t = pose.translation();
  return indent + "translation: " + list({t.x(), t.y(), t.z()}) + "  # metres\n" + indent +
         "rotation: " + list(orientationValues(pose.linear(), Orientation::Quaternion)) + "  # w x y z\n" + indent +
         "convention: quaternion\n";
}

}  // namespace binpick::core
