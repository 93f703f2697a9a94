// The singular places of the conventions (gimbal lock, half turns, tiny rotations) and the
// values rotationFromValues refuses.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "binpick/core/orientation.hpp"
#include "protocol_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::robot {
namespace {

using test::rotationX;
using test::rotationY;
using test::rotationZ;

void expectValues(const std::vector<double>& actual, const std::vector<double>& expected, double tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t k = 0; k < actual.size(); ++k) EXPECT_NEAR(actual[k], expected[k], tolerance) << k;
}

// Rz(a) Ry(+-90) Rx(c) = Rz(a -+ c) Ry(+-90): A takes the whole turn about the common axis.
TEST(ProtocolOrientationSingular, KukaGimbalLockPutsTheTurnIntoA) {
  expectValues(core::orientationValues(rotationZ(30) * rotationY(90) * rotationX(10), core::Orientation::EulerZYX),
               {20, 90, 0}, 1e-9);
  expectValues(core::orientationValues(rotationZ(30) * rotationY(-90) * rotationX(10), core::Orientation::EulerZYX),
               {40, -90, 0}, 1e-9);
  // FANUC lists the same angles the other way round: W is 0 and R takes the turn.
  expectValues(core::orientationValues(rotationZ(30) * rotationY(90) * rotationX(10), core::Orientation::FixedXYZ),
               {0, 90, 20}, 1e-9);
}

// Rx(a) Ry(+-90) Rz(c) = Rx(a +- c) Ry(+-90).
TEST(ProtocolOrientationSingular, StaubliGimbalLockPutsTheTurnIntoRx) {
  expectValues(core::orientationValues(rotationX(30) * rotationY(90) * rotationZ(10), core::Orientation::EulerXYZ),
               {40, 90, 0}, 1e-9);
  expectValues(core::orientationValues(rotationX(30) * rotationY(-90) * rotationZ(10), core::Orientation::EulerXYZ),
               {20, -90, 0}, 1e-9);
}

// At +-90 exactly and within 1e-9 degrees of it: the rule applies and R is reproduced. A little
// further out (1e-6 degrees) the angles are ill-determined one by one, but R must still be.
TEST(ProtocolOrientationSingular, NearGimbalLockTheRotationComesBackExactly) {
  std::mt19937 random(21);
  std::uniform_real_distribution<double> outer(-179.0, 179.0);
  for (double offset : {0.0, 1e-9, -1e-9, 1e-6, -1e-6, 1e-4}) {
    for (double lock : {90.0, -90.0}) {
      const double middle = lock - (lock > 0 ? 1.0 : -1.0) * std::abs(offset);
      for (int i = 0; i < 200; ++i) {
        const double a = outer(random), c = outer(random);
        const Eigen::Matrix3d zyx = rotationZ(a) * rotationY(middle) * rotationX(c);
        const Eigen::Matrix3d xyz = rotationX(a) * rotationY(middle) * rotationZ(c);
        const std::vector<double> abc = core::orientationValues(zyx, core::Orientation::EulerZYX);
        const std::vector<double> staubli = core::orientationValues(xyz, core::Orientation::EulerXYZ);
        ASSERT_TRUE(core::rotationFromValues(abc, core::Orientation::EulerZYX).isApprox(zyx, 1e-9)) << offset;
        ASSERT_TRUE(core::rotationFromValues(staubli, core::Orientation::EulerXYZ).isApprox(xyz, 1e-9)) << offset;
        EXPECT_NEAR(abc[1], middle, 1e-7);
        EXPECT_NEAR(staubli[1], middle, 1e-7);
        if (std::abs(offset) <= 1e-9) {
          EXPECT_EQ(abc[2], 0.0);
          EXPECT_EQ(staubli[2], 0.0);
        }
      }
    }
  }
}

TEST(ProtocolOrientationSingular, HalfTurnRotationVectorsHaveLengthPi) {
  std::mt19937 random(22);
  std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                       Eigen::Vector3d(1, 1, 1).normalized()};
  for (int i = 0; i < 1000; ++i) axes.push_back(test::randomRotation(random).col(0));
  for (const Eigen::Vector3d& axis : axes) {
    for (double angle : {test::kPi, test::kPi - 1e-10, test::kPi - 1e-6}) {
      const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      const std::vector<double> values = core::orientationValues(R, core::Orientation::RotationVector);
      const Eigen::Vector3d rotationVector(values[0], values[1], values[2]);
      EXPECT_NEAR(rotationVector.norm(), angle, 1e-9);
      EXPECT_NEAR(std::abs(rotationVector.normalized().dot(axis)), 1.0, 1e-9);
      ASSERT_TRUE(core::rotationFromValues(values, core::Orientation::RotationVector).isApprox(R, 1e-9));
    }
  }
}

TEST(ProtocolOrientationSingular, TinyRotationVectorsKeepTheirRelativePrecision) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 3).normalized();
  for (double angle : {1e-15, 1e-12, 1e-8, 1e-4}) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const std::vector<double> values = core::orientationValues(R, core::Orientation::RotationVector);
    const Eigen::Vector3d expected = angle * axis;
    // R itself only holds angle to ~1e-16 absolute: compare relative above that.
    EXPECT_LE((Eigen::Vector3d(values[0], values[1], values[2]) - expected).norm(), 1e-9 * angle + 2e-16);
  }
}

TEST(ProtocolOrientationSingular, QuaternionsAreNormalisedAndSignedWithWNonNegative) {
  expectValues(core::orientationValues(core::rotationFromValues({2, 0, 0, 0}, core::Orientation::Quaternion),
                                       core::Orientation::Quaternion),
               {1, 0, 0, 0}, 1e-15);
  // -q is the same rotation as q: it comes back as q.
  const double h = std::sqrt(0.5);
  expectValues(core::orientationValues(core::rotationFromValues({-h, 0, 0, -h}, core::Orientation::Quaternion),
                                       core::Orientation::Quaternion),
               {h, 0, 0, h}, 1e-12);
}

TEST(ProtocolOrientationSingular, BadValuesAreRefusedNamingTheProblem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(test::throwsNaming(
      [] {
        core::rotationFromValues({1, 0, 0}, core::Orientation::Quaternion);
      },
      "must be 4 numbers (got 3)"));
  EXPECT_TRUE(test::throwsNaming(
      [] {
        core::rotationFromValues({0, 0, 0, 0}, core::Orientation::EulerZYX);
      },
      "must be 3 numbers (got 4)"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        core::rotationFromValues({0, nan, 0}, core::Orientation::FixedXYZ);
      },
      "fixed_xyz) must be finite"));
  EXPECT_TRUE(test::throwsNaming(
      [&] {
        core::rotationFromValues({inf, 0, 0}, core::Orientation::RotationVector);
      },
      "must be finite"));
  EXPECT_TRUE(test::throwsNaming(
      [] {
        core::rotationFromValues({0, 0, 0, 0}, core::Orientation::Quaternion);
      },
      "zero quaternion"));
  EXPECT_TRUE(test::throwsNaming(
      [] {
        core::rotationFromValues({1e-12, 0, 0, 0}, core::Orientation::Quaternion);
      },
      "zero quaternion"));
}

TEST(ProtocolOrientationSingular, NamesRoundTripAndUnknownNamesListTheKnownOnes) {
  for (core::Orientation orientation :
       {core::Orientation::Quaternion, core::Orientation::EulerZYX, core::Orientation::FixedXYZ,
        core::Orientation::RotationVector, core::Orientation::EulerXYZ}) {
    EXPECT_EQ(core::orientationFromName(core::orientationName(orientation)), orientation);
  }
  EXPECT_EQ(core::orientationName(core::Orientation::FixedXYZ), "fixed_xyz");
  EXPECT_TRUE(test::throwsNaming([] { core::orientationFromName("Euler_ZYX"); },
                                 "'Euler_ZYX' is unknown: use quaternion, euler_zyx"));
}

}  // namespace
}  // namespace binpick::robot
