// Poses in settings files: what binpickd's settings, grasps files and hand_eye.yaml read.
#include <gtest/gtest.h>

#include <cmath>

#include "binpick/core/pose_yaml.hpp"
#include "thrown_message.hpp"

namespace binpick::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

YamlSection sectionOf(const std::string& yaml) { return YamlSection(parseYaml(yaml, "test.yaml"), "", "test.yaml"); }

double angleBetweenDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / kPi;
}

TEST(PoseYaml, ReadsEveryConventionToTheSameRotation) {
  // A quarter turn about z, as each controller's pendant shows it.
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (const std::string& rotation : {std::string("rotation: [0.7071067811865476, 0, 0, 0.7071067811865476]"),
                                      std::string("rotation: [90, 0, 0], convention: euler_zyx"),
                                      std::string("rotation: [0, 0, 90], convention: fixed_xyz"),
                                      std::string("rotation: [0, 0, 1.5707963267948966], convention: rotation_vector"),
                                      std::string("rotation: [0, 0, 90], convention: euler_xyz")}) {
    const Eigen::Isometry3d pose = readPose(sectionOf("{translation: [0.6, -0.1, 0.25], " + rotation + "}"));
    EXPECT_LT(angleBetweenDeg(pose.linear(), expected), 1e-9) << rotation;
    EXPECT_LT((pose.translation() - Eigen::Vector3d(0.6, -0.1, 0.25)).norm(), 1e-12) << rotation;
  }
}

TEST(PoseYaml, OptionalFieldsDefaultToNoMotion) {
  const Eigen::Isometry3d translated = readPose(sectionOf("{translation: [0.6, 0, 0]}"));
  EXPECT_TRUE(translated.linear().isIdentity(0.0));
  EXPECT_EQ(translated.translation(), Eigen::Vector3d(0.6, 0, 0));
  EXPECT_TRUE(readPose(sectionOf("{rotation: [1, 0, 0, 0]}")).translation().isZero(0.0));
}

TEST(PoseYaml, RequiredFieldsMustBeThere) {
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{translation: [0, 0, 1]}"), PoseFields::Required); },
                                 "rotation is missing"));
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{rotation: [1, 0, 0, 0]}"), PoseFields::Required); },
                                 "translation is missing"));
}

TEST(PoseYaml, BadValuesAreNamed) {
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{translation: [0, .nan, 1]}")); }, "translation"));
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{rotation: [0, 0, 0, 0]}")); }, "rotation"));
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{rotation: [1, 2], convention: euler_zyx}")); }, "rotation"));
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{rotation: [1, 0, 0], convention: abb}")); }, "rotation"));
  EXPECT_TRUE(test::throwsNaming([] { readPose(sectionOf("{translation: [0, 0, 0], scale: 2}")); }, "scale"));
}

TEST(PoseYaml, WrittenPosesReadBackToBelowANanometreAndANanoradian) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.612345678912, -0.0001234, 1.5);
  const Eigen::Isometry3d back = readPose(sectionOf(poseYaml(pose, "")), PoseFields::Required);
  EXPECT_LT((back.translation() - pose.translation()).norm(), 1e-9);
  EXPECT_LT(angleBetweenDeg(back.linear(), pose.linear()) * kPi / 180.0, 1e-9);
}

}  // namespace
}  // namespace binpick::core
