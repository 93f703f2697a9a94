// Each brand's orientation convention against rotations built independently from Eigen
// AngleAxis products, over many seeded random rotations and at the singular places.
#include <gtest/gtest.h>

#include <vector>

#include "binpick/io/robot_orientation.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

using test::rotationX;
using test::rotationY;
using test::rotationZ;

constexpr Orientation kAll[] = {Orientation::Quaternion, Orientation::EulerZYX,
                                Orientation::FixedXYZ, Orientation::RotationVector,
                                Orientation::EulerXYZ};
constexpr int kSamples = 10000;

// The rotation the values stand for, written straight from the brands' definitions.
Eigen::Matrix3d reference(const std::vector<double>& v, Orientation orientation) {
  switch (orientation) {
    case Orientation::Quaternion:
      return Eigen::Quaterniond(v[0], v[1], v[2], v[3]).normalized().toRotationMatrix();
    case Orientation::EulerZYX: return rotationZ(v[0]) * rotationY(v[1]) * rotationX(v[2]);
    case Orientation::FixedXYZ: return rotationZ(v[2]) * rotationY(v[1]) * rotationX(v[0]);
    case Orientation::EulerXYZ: return rotationX(v[0]) * rotationY(v[1]) * rotationZ(v[2]);
    case Orientation::RotationVector: {
      const Eigen::Vector3d r(v[0], v[1], v[2]);
      if (r.norm() == 0.0) return Eigen::Matrix3d::Identity();
      return Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
    }
  }
  return Eigen::Matrix3d::Zero();
}

void expectInRange(const std::vector<double>& v, Orientation orientation) {
  if (orientation == Orientation::Quaternion) {
    EXPECT_GE(v[0], 0.0);
    EXPECT_NEAR(Eigen::Vector4d(v[0], v[1], v[2], v[3]).norm(), 1.0, 1e-12);
  } else if (orientation == Orientation::RotationVector) {
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
    for (Orientation orientation : kAll) {
      const std::vector<double> values = orientationValues(R, orientation);
      ASSERT_EQ(values.size(), static_cast<std::size_t>(orientationValueCount(orientation)));
      expectInRange(values, orientation);
      ASSERT_TRUE(reference(values, orientation).isApprox(R, 1e-9)) << orientationName(orientation);
      ASSERT_TRUE(rotationFromValues(values, orientation).isApprox(R, 1e-9));
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
    for (Orientation orientation :
         {Orientation::EulerZYX, Orientation::FixedXYZ, Orientation::EulerXYZ}) {
      const std::vector<double> back =
          orientationValues(reference(euler, orientation), orientation);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(back[k], euler[k], 1e-9);
    }
    const Eigen::Matrix3d R = test::randomRotation(random);
    const Eigen::Vector3d rotationVector = angle(random) * Eigen::AngleAxisd(R).axis();
    const std::vector<double> rv = {rotationVector.x(), rotationVector.y(), rotationVector.z()};
    const std::vector<double> rvBack =
        orientationValues(reference(rv, Orientation::RotationVector), Orientation::RotationVector);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(rvBack[k], rv[k], 1e-9);
    const std::vector<double> q = orientationValues(R, Orientation::Quaternion);
    const std::vector<double> qBack =
        orientationValues(rotationFromValues(q, Orientation::Quaternion), Orientation::Quaternion);
    for (int k = 0; k < 4; ++k) ASSERT_NEAR(qBack[k], q[k], 1e-9);
  }
}

TEST(ProtocolOrientation, KukaAbcAndFanucWprAreTheSameAnglesInReverseOrder) {
  std::mt19937 random(13);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(random);
    const std::vector<double> abc = orientationValues(R, Orientation::EulerZYX);
    const std::vector<double> wpr = orientationValues(R, Orientation::FixedXYZ);
    EXPECT_EQ(wpr, (std::vector<double>{abc[2], abc[1], abc[0]}));
  }
}

TEST(ProtocolOrientation, IdentityIsZeroAnglesAndTheUnitQuaternion) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (Orientation orientation : kAll) {
    std::vector<double> expected(static_cast<std::size_t>(orientationValueCount(orientation)), 0.0);
    if (orientation == Orientation::Quaternion) expected[0] = 1.0;
    const std::vector<double> values = orientationValues(I, orientation);
    for (std::size_t k = 0; k < values.size(); ++k) EXPECT_NEAR(values[k], expected[k], 1e-15);
    EXPECT_TRUE(rotationFromValues(values, orientation).isApprox(I, 1e-15));
  }
}

// Exact half-turn matrices, with the zero signs atan2 turns into -180 if nothing corrects it.
TEST(ProtocolOrientation, HalfTurnsAreAnglesOf180NotMinus180) {
  Eigen::Matrix3d halfTurnZ = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  Eigen::Matrix3d halfTurnX = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  halfTurnZ(1, 0) = -0.0;
  halfTurnX(2, 1) = -0.0;
  halfTurnX(1, 2) = -0.0;
  EXPECT_EQ(orientationValues(halfTurnZ, Orientation::EulerZYX)[0], 180.0);
  EXPECT_EQ(orientationValues(halfTurnX, Orientation::EulerZYX)[2], 180.0);
  EXPECT_EQ(orientationValues(halfTurnX, Orientation::FixedXYZ)[0], 180.0);
  EXPECT_EQ(orientationValues(halfTurnX, Orientation::EulerXYZ)[0], 180.0);
  EXPECT_EQ(orientationValues(halfTurnZ, Orientation::EulerXYZ)[2], 180.0);
  EXPECT_NEAR(orientationValues(rotationZ(179.999), Orientation::EulerXYZ)[2], 179.999, 1e-9);
  EXPECT_NEAR(orientationValues(rotationZ(-179.999), Orientation::EulerZYX)[0], -179.999, 1e-9);
}

}  // namespace
}  // namespace binpick::robot
