#pragma once
// Volume, centre of mass and inertia of a closed triangle mesh of uniform density, and the frame a
// rigid body simulation wants: centred on the centre of mass, axes along the principal axes of
// inertia (Bullet takes a diagonal inertia tensor in the body frame). Internal to
// binpick::simulation. Pure functions: thread-safe.
#include <Eigen/Geometry>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation::detail {

struct MassProperties {
  double volume = 0.0;                                 // m^3, positive for outward normals
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // model frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   // about the centroid, per unit density
};

MassProperties massProperties(const io::TriangleMesh& mesh);

struct PrincipalFrame {
  Eigen::Isometry3d T_model_body = Eigen::Isometry3d::Identity();  // proper rotation, at centroid
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();               // principal moments per unit density, m^5
  double volume = 0.0;
};

PrincipalFrame principalFrame(const MassProperties& mass);

}  // namespace binpick::simulation::detail
