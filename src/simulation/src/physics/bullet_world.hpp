#pragma once
// A Bullet dynamics world holding the bin (floor and walls as static boxes) and the dropped parts,
// in the bin frame scaled to world units (bullet_units.hpp). Single-threaded and deterministic:
// the same sequence of calls gives bit-identical results. Internal to binpick::simulation; not
// copyable, and not to be used from two threads at once.
#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "binpick/simulation/physics_pile.hpp"
#include "part_shape.hpp"

namespace binpick::simulation::detail {

class BulletWorld {
 public:
  BulletWorld(const BinInterior& bin, const PhysicsParams& params);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  // A new body of `part` (which must outlive the world) with its model frame at T_bin_model.
  btRigidBody* addPart(const PartShape& part, const Eigen::Isometry3d& T_bin_model);
  void removePart(btRigidBody* body);

  void step(double seconds);

 private:
  void addStaticBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
  btScalar rollingFriction() const;

  PhysicsParams params_;
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btBoxShape>> boxes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;  // static boxes, then parts
};

}  // namespace binpick::simulation::detail
