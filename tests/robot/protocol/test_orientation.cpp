// Each brand's orientation convention against rotations built independently from Eigen
// AngleAxis products, over many seeded random rotations and at the singular places.
#include <gtest/gtest.h>

#include <vector>

#include "binpick/core/orientation.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

using test::rotationX;
using test::rotationY;
using test::rotationZ;

constexpr core::Orientation kAll[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                      core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                      core::Orientation::EulerXYZ};
constexpr int kSamples = 10000;

// The rotation the values stand for, written straight from the brands' definitions.
Eigen::Matrix3d reference(const std::vector<double>& v, core::Orientation orientation) {
  switch (orientation) {
    case core::Orientation::Quaternion:
      return Eigen::Quaterniond(v[0], v[1], v[2], v[3]).normalized().toRotationMatrix();
    case core::Orientation::EulerZYX: return rotationZ(v[0]) * rotationY(v[1]) * rotationX(v[2]);
    case core::Orientation::FixedXYZ: return rotationZ(v[2]) * rotationY(v[1]) * rotationX(v[0]);
    case core::Orientation::EulerXYZ: return rotationX(v[0]) * rotationY(v[1]) * rotationZ(v[2]);
    case core::Orientation::RotationVector: {
      const Eigen::Vector3d r(v[0], v[1], v[2]);
      if (r.norm() == 0.0) return Eigen::Matrix3d::Identity();
      return Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
    }
  }
  return Eigen::Matrix3d::Zero();
}

void expectInRange(const std::vector<double>& v, core::Orientation orientation) {
  if (orientation == core::Orientation::Quaternion) {
    EXPECT_GE(v[0], 0.0);
    EXPECT_NEAR(Eigen::Vector4d(v[0], v[1], v[2], v[3]).norm(), 1.0, 1e-12);
  } else if (orientation == core::Orientation::RotationVector) {
    EXPECT_LE(Eigen::Vector3d(v[0], v[1], v[2]).norm(), test::kPi + 1e-12);
  } else {
    for (double angle : v) {
      EXPECT_GT(angle, -180.0);
      EXPECT_LE(angle, 180.0);
    }
    EXPECT_LE(std::abs(v[1]), 90.0);
  }
}

TEST(ProtocolOrientation, ValuesDescribeTheRotationAndComeBackToIt) {
  std::mt19937 random(11);
  for (int i = 0; i < kSamples; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(random);
    for (core::Orientation orientation : kAll) {
      const std::vector<double> values = core::orientationValues(R, orientation);
      ASSERT_EQ(values.size(), static_cast<std::size_t>(core::orientationValueCount(orientation)));
      expectInRange(values, orientation);
      ASSERT_TRUE(reference(values, orientation).isApprox(R, 1e-9)) << core::orientationName(orientation);
      ASSERT_TRUE(core::rotationFromValues(values, orientation).isApprox(R, 1e-9));
    }
  }
}

// Values in range -> R -> the same values (away from the singular places, where they are not
// unique: tested below).
TEST(ProtocolOrientation, ValuesInRangeComeBackUnchanged) {
  std::mt19937 random(12);
  std::uniform_real_distribution<double> outer(-179.9, 179.9), middle(-89.9, 89.9);
  std::uniform_real_distribution<double> angle(0.0, test::kPi - 1e-3);
  for (int i = 0; i < kSamples; ++i) {
    const std::vector<double> euler = {outer(random), middle(random), outer(random)};
    for (core::Orientation orientation :
         {core::Orientation::EulerZYX, core::Orientation::FixedXYZ, core::Orientation::EulerXYZ}) {
      const std::vector<double> back = core::orientationValues(reference(euler, orientation), orientation);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(back[k], euler[k], 1e-9);
    }
    const Eigen::Matrix3d R = test::randomRotation(random);
    const Eigen::Vector3d rotationVector = angle(random) * Eigen::AngleAxisd(R).axis();
    const std::vector<double> rv = {rotationVector.x(), rotationVector.y(), rotationVector.z()};
    const std::vector<double> rvBack =
        core::orientationValues(reference(rv, core::Orientation::RotationVector), core::Orientation::RotationVector);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(rvBack[k], rv[k], 1e-9);
    const std::vector<double> q = core::orientationValues(R, core::Orientation::Quaternion);
    const std::vector<double> qBack = core::orientationValues(
        core::rotationFromValues(q, core::Orientation::Quaternion), core::Orientation::Quaternion);
    for (int k = 0; k < 4; ++k) ASSERT_NEAR(qBack[k], q[k], 1e-9);
  }
}

TEST(ProtocolOrientation, KukaAbcAndFanucWprAreTheSameAnglesInReverseOrder) {
  std::mt19937 random(13);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(random);
    const std::vector<double> abc = core::orientationValues(R, core::Orientation::EulerZYX);
    const std::vector<double> wpr = core::orientationValues(R, core::Orientation::FixedXYZ);
    EXPECT_EQ(wpr, (std::vector<double>{abc[2], abc[1], abc[0]}));
  }
}

TEST(ProtocolOrientation, IdentityIsZeroAnglesAndTheUnitQuaternion) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (core::Orientation orientation : kAll) {
    std::vector<double> expected(static_cast<std::size_t>(core::orientationValueCount(orientation)), 0.0);
    if (orientation == core::Orientation::Quaternion) expected[0] = 1.0;
    const std::vector<double> values = core::orientationValues(I, orientation);
    for (std::size_t k = 0; k < values.size(); ++k) EXPECT_NEAR(values[k], expected[k], 1e-15);
    EXPECT_TRUE(core::rotationFromValues(values, orientation).isApprox(I, 1e-15));
  }
}

// Exact half-turn matrices, with the zero signs atan2 turns into -180 if nothing corrects it.
TEST(ProtocolOrientation, HalfTurnsAreAnglesOf180NotMinus180) {
  Eigen::Matrix3d halfTurnZ = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  Eigen::Matrix3d halfTurnX = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  halfTurnZ(1, 0) = -0.0;
  halfTurnX(2, 1) = -0.0;
  halfTurnX(1, 2) = -0.0;
  EXPECT_EQ(core::orientationValues(halfTurnZ, core::Orientation::EulerZYX)[0], 180.0);
  EXPECT_EQ(core::orientationValues(halfTurnX, core::Orientation::EulerZYX)[2], 180.0);
  EXPECT_EQ(core::orientationValues(halfTurnX, core::Orientation::FixedXYZ)[0], 180.0);
  EXPECT_EQ(core::orientationValues(halfTurnX, core::Orientation::EulerXYZ)[0], 180.0);
  EXPECT_EQ(core::orientationValues(halfTurnZ, core::Orientation::EulerXYZ)[2], 180.0);
  EXPECT_NEAR(core::orientationValues(rotationZ(179.999), core::Orientation::EulerXYZ)[2], 179.999, 1e-9);
  EXPECT_NEAR(core::orientationValues(rotationZ(-179.999), core::Orientation::EulerZYX)[0], -179.999, 1e-9);
}

}  // namespace
}  // namespace binpick::robot
