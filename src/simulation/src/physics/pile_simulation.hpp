#pragma once
// The running simulation of one pile: releases parts into the Bullet world, steps it until the
// parts come to rest, and takes out parts that ended outside the bin. Internal to
// binpick::simulation; not copyable, not for concurrent use.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/simulation/physics_pile.hpp"
#include "bullet_world.hpp"
#include "part_shape.hpp"

namespace binpick::simulation::detail {

class PileSimulation {
 public:
  // `part` must outlive the simulation.
  PileSimulation(const PartShape& part, const BinInterior& bin, const PhysicsParams& params);

  // Highest point of any part in the world (0, the floor, when there is none). Metres, bin frame.
  double pileTop() const;
  // Adds the parts; each gets the next serial number (0, 1, ... over the simulation's life).
  void release(const std::vector<Eigen::Isometry3d>& T_bin_model);

  // Steps until every part has come to rest (true), or until `frame_limit` time steps have been
  // simulated since the simulation began (false).
  bool settle(int frame_limit);
  // Takes out every part not inside the bin (see isInsideBin), and those that fell off the world
  // while settling; returns their serial numbers.
  std::vector<int> removeEscaped();
  // Takes out the part at `index` (release order) and wakes all others: a body Bullet has put to
  // sleep stays where it is, supported or not, until something wakes it.
  void removeAt(int index);

  std::vector<Eigen::Isometry3d> poses() const;  // T_bin_model of the parts, in release order
  std::vector<int> serials() const;              // of the parts, in release order
  int size() const { return static_cast<int>(bodies_.size()); }
  int frames() const { return frames_; }  // time steps simulated
  long steps() const { return static_cast<long>(frames_) * params_.substeps; }
  double simulatedTime() const { return frames_ * params_.time_step; }

 private:
  Eigen::Isometry3d T_bin_model(const btRigidBody* body) const;
  bool atRest(const btRigidBody* body, const btTransform& window_start, double window) const;
  bool isInsideBin(const btRigidBody* body) const;
  bool removeFallen();  // true if any
  void remove(btRigidBody* body);

  const PartShape& part_;
  BinInterior bin_;
  PhysicsParams params_;
  BulletWorld world_;
  std::vector<btRigidBody*> bodies_;  // in release order; each one's user index is its serial
  int frames_ = 0;                    // time steps simulated
  int next_serial_ = 0;
  std::vector<int> fallen_;  // serials taken out while falling off the world
};

}  // namespace binpick::simulation::detail
