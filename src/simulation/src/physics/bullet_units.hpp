#pragma once
// Conversions between the library's SI frames and the Bullet world's units.
//
// Bullet's built-in tolerances are absolute lengths chosen for objects of about a metre: the
// default collision margin (0.04), the contact breaking threshold (0.02), the penetration depth
// beyond which split impulses take over (0.04) and the GJK/EPA epsilons (1e-4). For parts of 40 to
// 120 mm in metres those would be 4 cm margins and 2 cm contact distances, and the solver would
// push parts apart with velocity impulses (adding bounce) instead of position corrections.
// Simulating in centimetres makes them 0.4 mm, 0.2 mm, 0.4 mm and 1 um: right for such parts.
// Time is not scaled, so velocities and gravity scale like lengths; masses stay in kilograms.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include <LinearMath/btTransform.h>

#include <Eigen/Geometry>

namespace binpick::simulation::detail {

constexpr double kWorldScale = 100.0;  // Bullet length units per metre

inline btVector3 toWorld(const Eigen::Vector3d& metres) {
  const Eigen::Vector3d v = kWorldScale * metres;
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

inline Eigen::Vector3d toMetres(const btVector3& world) {
  return Eigen::Vector3d(world.x(), world.y(), world.z()) / kWorldScale;
}

inline btTransform toWorld(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                  static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                     toWorld(Eigen::Vector3d(pose.translation())));
}

// Through the quaternion, renormalised in double: the rotation is orthonormal to double precision
// even though Bullet keeps it in single precision.
inline Eigen::Isometry3d toMetres(const btTransform& world) {
  const btQuaternion r = world.getRotation();
  const Eigen::Quaterniond q(r.w(), r.x(), r.y(), r.z());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = toMetres(world.getOrigin());
  return pose;
}

}  // namespace binpick::simulation::detail
