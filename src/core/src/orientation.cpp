#include "binpick/core/orientation.hpp"

#include <cmath>
#include <sstream>

#include "binpick/core/error.hpp"

namespace binpick::core {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegreesPerRadian = 180.0 / kPi;

// Within this distance (radians) of +-90 degrees the middle angle counts as gimbal lock: the
// first and last axes coincide there, so only their sum or difference is defined. Rotation
// matrices carry ~1e-16 rounding, which alone decides the split just outside this band; inside
// it the split is fixed by the documented rule instead of by noise.
constexpr double kGimbalLockBand = 1e-9;

// A quaternion shorter than this is no rotation, even after normalising.
constexpr double kMinQuaternionNorm = 1e-9;

struct Angles {
  double first, middle, last;  // radians
};

// (-180, 180] in degrees. atan2 may return -pi, the same angle as +pi.
double toDegreesInRange(double radians) {
  double degrees = radians * kDegreesPerRadian;
  if (degrees <= -180.0) degrees += 360.0;
  if (degrees > 180.0) degrees -= 360.0;
  return degrees;
}

Eigen::Matrix3d rotationX(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
}
Eigen::Matrix3d rotationY(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Eigen::Matrix3d rotationZ(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// R = Rz(first) Ry(middle) Rx(last). The last angle comes from the third row; the first is then
// read from R Rx(-last), whose second column is (-sin first, cos first, 0) whatever the middle
// angle: well conditioned even next to gimbal lock, where the third row is nearly zero and the
// last angle is poorly determined (the first one absorbs its error exactly).
Angles decomposeZYX(const Eigen::Matrix3d& R) {
  const double cosMiddle = std::hypot(R(2, 1), R(2, 2));
  Angles angles{};
  angles.middle = std::atan2(-R(2, 0), cosMiddle);
  angles.last = cosMiddle < kGimbalLockBand ? 0.0 : std::atan2(R(2, 1), R(2, 2));
  const Eigen::Matrix3d firstAndMiddle = R * rotationX(-angles.last);
  angles.first = std::atan2(-firstAndMiddle(0, 1), firstAndMiddle(1, 1));
  return angles;
}

// R = Rx(first) Ry(middle) Rz(last): the mirror image of decomposeZYX. The first row holds
// (cos m cos l, -cos m sin l, sin m); R Rz(-last) has the second row (0, cos first, sin first).
Angles decomposeXYZ(const Eigen::Matrix3d& R) {
  const double cosMiddle = std::hypot(R(0, 0), R(0, 1));
  Angles angles{};
  angles.middle = std::atan2(R(0, 2), cosMiddle);
  angles.last = cosMiddle < kGimbalLockBand ? 0.0 : std::atan2(-R(0, 1), R(0, 0));
  const Eigen::Matrix3d firstAndMiddle = R * rotationZ(-angles.last);
  angles.first = std::atan2(firstAndMiddle(2, 1), firstAndMiddle(1, 1));
  return angles;
}

std::vector<double> quaternionValues(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // q and -q are the same rotation
  return {q.w(), q.x(), q.y(), q.z()};
}

// axis * angle from the unit quaternion (w >= 0): angle = 2 atan2(|v|, w) is accurate near 0
// and near pi, unlike acos((trace - 1) / 2). Near 0 the factor angle / |v| tends to 2 / w.
std::vector<double> rotationVectorValues(const Eigen::Matrix3d& R) {
  const std::vector<double> q = quaternionValues(R);
  const Eigen::Vector3d v(q[1], q[2], q[3]);
  const double sinHalf = v.norm();
  const double factor = sinHalf > 1e-12 ? 2.0 * std::atan2(sinHalf, q[0]) / sinHalf : 2.0 / q[0];
  const Eigen::Vector3d rotationVector = factor * v;
  return {rotationVector.x(), rotationVector.y(), rotationVector.z()};
}

void requireValues(bool ok, Orientation orientation, const std::string& problem) {
  if (ok) return;
  throw Error("orientation values (" + orientationName(orientation) + ") " + problem);
}

Eigen::Matrix3d rotationFromQuaternion(const std::vector<double>& values) {
  Eigen::Quaterniond q(values[0], values[1], values[2], values[3]);
  requireValues(q.norm() >= kMinQuaternionNorm, Orientation::Quaternion, "must not be a zero quaternion");
  return q.normalized().toRotationMatrix();
}

Eigen::Matrix3d rotationFromRotationVector(const std::vector<double>& values) {
  const Eigen::Vector3d rotationVector(values[0], values[1], values[2]);
  const double angle = rotationVector.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotationVector / angle).toRotationMatrix();
}

double radians(double degrees) { return degrees / kDegreesPerRadian; }

}  // namespace

Orientation orientationFromName(const std::string& name) {
  for (Orientation orientation : {Orientation::Quaternion, Orientation::EulerZYX, Orientation::FixedXYZ,
                                  Orientation::RotationVector, Orientation::EulerXYZ}) {
    if (orientationName(orientation) == name) return orientation;
  }
  throw Error("orientation '" + name +
              "' is unknown: use quaternion, euler_zyx, fixed_xyz, rotation_vector or euler_xyz");
}

std::string orientationName(Orientation orientation) {
  switch (orientation) {
    case Orientation::Quaternion: return "quaternion";
    case Orientation::EulerZYX: return "euler_zyx";
    case Orientation::FixedXYZ: return "fixed_xyz";
    case Orientation::RotationVector: return "rotation_vector";
    case Orientation::EulerXYZ: return "euler_xyz";
  }
  return "unknown";
}

int orientationValueCount(Orientation orientation) { return orientation == Orientation::Quaternion ? 4 : 3; }

std::vector<double> orientationValues(const Eigen::Matrix3d& R, Orientation orientation) {
  switch (orientation) {
    case Orientation::Quaternion: return quaternionValues(R);
    case Orientation::RotationVector: return rotationVectorValues(R);
    case Orientation::EulerZYX: {
      const Angles a = decomposeZYX(R);
      return {toDegreesInRange(a.first), toDegreesInRange(a.middle), toDegreesInRange(a.last)};
    }
    case Orientation::FixedXYZ: {  // W, P, R: the same angles as A, B, C, listed x first
      const Angles a = decomposeZYX(R);
      return {toDegreesInRange(a.last), toDegreesInRange(a.middle), toDegreesInRange(a.first)};
    }
    case Orientation::EulerXYZ: {
      const Angles a = decomposeXYZ(R);
      return {toDegreesInRange(a.first), toDegreesInRange(a.middle), toDegreesInRange(a.last)};
    }
  }
  throw Error("orientation convention " + std::to_string(static_cast<int>(orientation)) + " is unknown");
}

Eigen::Matrix3d rotationFromValues(const std::vector<double>& values, Orientation orientation) {
  const std::size_t expected = static_cast<std::size_t>(orientationValueCount(orientation));
  requireValues(values.size() == expected, orientation,
                "must be " + std::to_string(expected) + " numbers (got " + std::to_string(values.size()) + ")");
  for (double value : values) requireValues(std::isfinite(value), orientation, "must be finite");
  switch (orientation) {
    case Orientation::Quaternion: return rotationFromQuaternion(values);
    case Orientation::RotationVector: return rotationFromRotationVector(values);
    case Orientation::EulerZYX:
      return rotationZ(radians(values[0])) * rotationY(radians(values[1])) * rotationX(radians(values[2]));
    case Orientation::FixedXYZ:
      return rotationZ(radians(values[2])) * rotationY(radians(values[1])) * rotationX(radians(values[0]));
    case Orientation::EulerXYZ:
      return rotationX(radians(values[0])) * rotationY(radians(values[1])) * rotationZ(radians(values[2]));
  }
  throw Error("orientation convention " + std::to_string(static_cast<int>(orientation)) + " is unknown");
}

}  // namespace binpick::core
