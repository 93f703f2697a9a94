#pragma once
// A part as Bullet sees it: its convex decomposition as a compound shape in the body frame (centre
// of mass, principal axes of inertia), in world units, with its mass and inertia. Built once per
// pile and shared by every copy of the part. Internal to binpick::simulation. Not copyable; read
// only once built (Bullet only reads shared shapes).
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/simulation/physics_pile.hpp"

namespace binpick::simulation::detail {

class PartShape {
 public:
  // `mesh` must be closed with outward normals (positive volume).
  PartShape(const io::TriangleMesh& mesh, const PhysicsParams& params);
  PartShape(const PartShape&) = delete;
  PartShape& operator=(const PartShape&) = delete;

  btCollisionShape* shape() const { return compound_.get(); }
  double mass() const { return mass_; }                  // kilograms
  const btVector3& inertia() const { return inertia_; }  // principal, world units
  const Eigen::Isometry3d& T_model_body() const { return T_model_body_; }
  // Model-frame points whose extent along any direction is the mesh's (the pieces' corners).
  const std::vector<Eigen::Vector3d>& extremePoints() const { return extreme_points_; }
  int pieces() const { return static_cast<int>(hulls_.size()); }

 private:
  std::vector<std::unique_ptr<btConvexHullShape>> hulls_;
  std::unique_ptr<btCompoundShape> compound_;
  double mass_ = 0.0;
  btVector3 inertia_;
  Eigen::Isometry3d T_model_body_ = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> extreme_points_;
};

}  // namespace binpick::simulation::detail
