#include "config_pose.hpp"

#include <vector>

#include "binpick/io/robot_orientation.hpp"

namespace binpick::cell {

Eigen::Isometry3d readPose(YamlSection section) {
  if (section.isNull()) section.fail("", "needs translation and rotation");
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
  if (values.empty()) return pose;
  try {
    const robot::Orientation convention = robot::orientationFromName(convention_name);
    pose.linear() = robot::rotationFromValues(values, convention);
  } catch (const Error& e) {
    section.fail("rotation", e.what());
  }
  return pose;
}

}  // namespace binpick::cell
