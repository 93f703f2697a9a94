#include <gtest/gtest.h>

#include "binpick/simulation/parts.hpp"

namespace binpick::simulation {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Isometry3d pose(const Eigen::AngleAxisd& rotation, const Eigen::Vector3d& translation) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation.toRotationMatrix();
  T.translation() = translation;
  return T;
}

Eigen::Isometry3d rotationOnly(double degrees, const Eigen::Vector3d& axis) {
  return pose(Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()), Eigen::Vector3d::Zero());
}

const Eigen::Isometry3d kTruth = pose(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()), {0.1, -0.2, 0.8});

TEST(PoseError, ZeroForIdenticalPoses) {
  const PoseError error = poseError(kTruth, kTruth, Symmetry{});
  EXPECT_NEAR(error.translation, 0.0, 1e-12);
  EXPECT_NEAR(error.rotation_deg, 0.0, 1e-6);
}

TEST(PoseError, KnownRotationAndTranslation) {
  Eigen::Isometry3d estimate = kTruth * rotationOnly(25.0, {0.3, -1, 0.2});
  estimate.translation() += Eigen::Vector3d(0.003, 0.0, -0.004);
  const PoseError error = poseError(estimate, kTruth, Symmetry{});
  EXPECT_NEAR(error.translation, 0.005, 1e-12);
  EXPECT_NEAR(error.rotation_deg, 25.0, 1e-9);
}

TEST(PoseError, TinyRotationIsStillAccurate) {
  const PoseError error = poseError(kTruth * rotationOnly(1e-4, {0, 0, 1}), kTruth, Symmetry{});
  EXPECT_NEAR(error.rotation_deg, 1e-4, 1e-9);
}

TEST(PoseError, WithoutSymmetryAHalfTurnIs180Degrees) {
  const PoseError error = poseError(kTruth * rotationOnly(180.0, {0, 0, 1}), kTruth, Symmetry{});
  EXPECT_NEAR(error.rotation_deg, 180.0, 1e-6);
}

TEST(PoseError, DeclaredHalfTurnSymmetryIsForgiven) {
  Symmetry half_turn_about_z;
  half_turn_about_z.discrete.push_back(rotationOnly(180.0, {0, 0, 1}).linear());
  const Eigen::Isometry3d flipped = kTruth * rotationOnly(180.0, {0, 0, 1});
  EXPECT_NEAR(poseError(flipped, kTruth, half_turn_about_z).rotation_deg, 0.0, 1e-6);
  // An extra 10 degrees on top of the symmetry is still measured.
  const Eigen::Isometry3d flipped_and_off = flipped * rotationOnly(10.0, {1, 0, 0});
  EXPECT_NEAR(poseError(flipped_and_off, kTruth, half_turn_about_z).rotation_deg, 10.0, 1e-6);
  // A half-turn about another axis is not a symmetry of this model.
  const Eigen::Isometry3d wrong_flip = kTruth * rotationOnly(180.0, {1, 0, 0});
  EXPECT_NEAR(poseError(wrong_flip, kTruth, half_turn_about_z).rotation_deg, 180.0, 1e-6);
}

TEST(PoseError, ContinuousAxisIgnoresSpinAboutIt) {
  Symmetry cylinder;
  cylinder.continuous_axis = Eigen::Vector3d::UnitZ();
  const Eigen::Isometry3d spun = kTruth * rotationOnly(73.0, {0, 0, 1});
  EXPECT_NEAR(poseError(spun, kTruth, cylinder).rotation_deg, 0.0, 1e-6);
  const Eigen::Isometry3d tilted = spun * rotationOnly(20.0, {1, 0, 0});
  EXPECT_NEAR(poseError(tilted, kTruth, cylinder).rotation_deg, 20.0, 1e-6);
}

TEST(PoseError, ContinuousAxisCombinesWithDiscreteFlip) {
  Symmetry capped_cylinder;
  capped_cylinder.continuous_axis = Eigen::Vector3d::UnitZ();
  capped_cylinder.discrete.push_back(rotationOnly(180.0, {1, 0, 0}).linear());
  const Eigen::Isometry3d upside_down = kTruth * rotationOnly(180.0, {0, 1, 0}) * rotationOnly(5.0, {1, 0, 0});
  EXPECT_NEAR(poseError(upside_down, kTruth, capped_cylinder).rotation_deg, 5.0, 1e-6);
  Symmetry plain_cylinder;
  plain_cylinder.continuous_axis = Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(poseError(upside_down, kTruth, plain_cylinder).rotation_deg, 175.0, 1e-6);
}

TEST(PoseError, TranslationIsMeasuredAtTheModelOrigin) {
  Symmetry cylinder;
  cylinder.continuous_axis = Eigen::Vector3d::UnitZ();
  Eigen::Isometry3d estimate = kTruth * rotationOnly(40.0, {0, 0, 1});
  estimate.translation() += Eigen::Vector3d(0.0, 0.002, 0.0);
  EXPECT_NEAR(poseError(estimate, kTruth, cylinder).translation, 0.002, 1e-12);
}

}  // namespace
}  // namespace binpick::simulation
