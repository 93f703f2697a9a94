#pragma once
// Orientation conventions of robot controllers. Values are what the brand's teach pendant shows:
//   Quaternion      ABB          q1..q4 = w, x, y, z (unit, w >= 0)
//   EulerZYX        KUKA         A, B, C degrees: R = Rz(A) Ry(B) Rx(C)
//   FixedXYZ        FANUC, Yaskawa W, P, R degrees: rotations about the fixed X, Y, Z axes in that
//                                order, R = Rz(R) Ry(P) Rx(W)
//   RotationVector  UR           rx, ry, rz radians: axis * angle, angle in [0, pi]
//   EulerXYZ        Staubli      rx, ry, rz degrees: about the moving X, Y', Z'' axes,
//                                R = Rx(rx) Ry(ry) Rz(rz)
// Angles come back in (-180, 180], the middle one in [-90, 90]. At gimbal lock (the middle angle
// within 1e-9 rad of +-90 degrees) the outer and inner axes coincide and only their sum or
// difference is defined: the outer rotation (leftmost factor of R) takes the whole of it and the
// inner one (rightmost factor) is 0. That is A (KUKA) and rx (Staubli), the first values, with C
// and rz 0; FANUC's W, P, R are KUKA's C, B, A listed in the other order, so there W is 0 and R
// takes the rotation. Quaternions have w >= 0 (the sign of the others is then fixed except at
// w = 0, a 180-degree turn, where q and -q both qualify); rotation vectors have the angle in
// [0, pi], at exactly pi either sign of the axis. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace binpick::core {

enum class Orientation { Quaternion, EulerZYX, FixedXYZ, RotationVector, EulerXYZ };

// "quaternion", "euler_zyx", "fixed_xyz", "rotation_vector", "euler_xyz"; throws core::Error
// listing the names for any other.
Orientation orientationFromName(const std::string& name);
std::string orientationName(Orientation orientation);
int orientationValueCount(Orientation orientation);  // 4 for quaternions, else 3

// R must be a rotation matrix.
std::vector<double> orientationValues(const Eigen::Matrix3d& R, Orientation orientation);
// The inverse; throws core::Error on a wrong count, a NaN or infinite value or a zero
// quaternion (norm below 1e-9; any other quaternion is normalised). Euler angles and rotation
// vectors may lie outside the ranges above: they wrap.
Eigen::Matrix3d rotationFromValues(const std::vector<double>& values, Orientation orientation);

}  // namespace binpick::core
