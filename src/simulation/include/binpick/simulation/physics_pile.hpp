#pragma once
// A physical pile: identical rigid parts dropped into a bin and simulated (Bullet) until they come
// to rest. Deterministic for a seed: the same inputs give bit-identical poses on the same build.
// simulatePile is stateless: every call builds its own world, so concurrent calls do not influence
// each other. A PhysicsBin keeps its world: parts are taken out one by one and the rest re-settle.
// (Bullet itself updates a few global statistics counters without locking; nothing reads them,
// but a race detector will report them when calls run on several threads.)
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation {

// The inside of the bin. Bin frame: origin at the centre of the floor's top face, x along the
// length, z up; the walls stand outside this area, from the floor up to wall_height.
struct BinInterior {
  double length = 0.40;       // metres, along x
  double width = 0.30;        // metres, along y
  double wall_height = 0.15;  // metres
};

// The bin as the rig sees it and as the physics holds it: a closed triangle mesh in the bin frame,
// the floor slab (10 mm thick, below z = 0) and four walls (10 mm thick) outside the interior.
// Throws core::Error unless the three sizes are positive and finite.
io::TriangleMesh binMesh(const BinInterior& bin);

struct PhysicsParams {
  // Parts are released in layers above whatever already lies in the bin: each part's lowest point
  // starts this far above the highest point of the pile (or of the floor), uniformly at random.
  // The next layer follows once the pile has come to rest.
  double drop_height_min = 0.02;  // metres
  double drop_height_max = 0.10;  // metres

  double friction = 0.5;     // Coulomb coefficient between two parts and between a part and the bin
  double restitution = 0.1;  // share of the approach speed kept after an impact, in [0, 1]
  // Lever arm of the torque that resists rolling and spinning on a contact, as a multiple of the
  // normal force. Without it a ring standing on its rim could roll around the bin for ever.
  double rolling_resistance = 0.0005;  // metres

  // The world advances in steps of time_step / substeps; settling and escapes are checked after
  // every time_step. Thin parts, or parts that fall far, need shorter steps not to pass through
  // each other.
  double time_step = 1.0 / 120.0;  // seconds
  int substeps = 2;
  double max_simulated_time = 30.0;  // seconds, all layers together; the run stops there
  // Budget of each PhysicsBin::remove: the rest of the pile re-settles within this much simulated
  // time or the call stops there (and reports it).
  double max_resettle_time = 5.0;  // seconds

  // The pile has come to rest when, over a window of settle_time, every part's centre of mass has
  // moved slower than settle_linear_velocity and the part has turned slower than
  // settle_angular_velocity, on average: the mean over a window is not kept up by the contact
  // solver's jitter as instantaneous velocities are.
  double settle_linear_velocity = 0.005;  // metres per second
  double settle_angular_velocity = 0.1;   // radians per second
  double settle_time = 0.2;               // seconds

  // Collision shape: a union of convex pieces containing the mesh, each reaching at most about
  // decomposition_tolerance beyond it. The reach is measured on a grid of cells half that size,
  // capped at 4 million cells: beyond about 80 x 80 x 80 mm (at 1 mm) the cells grow with the
  // part and the tolerance becomes twice the cell size, about 1/80 of a cubic part's size. If
  // max_convex_pieces is not enough to meet the tolerance, the shape is coarser where it must be.
  // The pieces follow the part's own axes or its principal axes of inertia, whichever box is
  // tighter; decomposing takes 0.03-0.15 s for the built-in parts and grows with the number of
  // triangles (about 1 s at 10 000).
  double decomposition_tolerance = 0.001;  // metres
  int max_convex_pieces = 48;
  // Bullet's contact shell around every convex piece (outwards: it adds to the shape); part to
  // part gaps at rest are about twice this.
  double collision_margin = 0.0004;  // metres

  // Throws core::Error naming the first bad field as `name`.field, e.g.
  // "PhysicsParams.friction".
  void validate(const std::string& name = "PhysicsParams") const;
};

struct PhysicsPile {
  // Every part that ended inside the bin, in the order of its (last) drop. All of a part's mesh
  // lies within the inner walls and above the floor, up to 0.5 mm.
  std::vector<Eigen::Isometry3d> T_bin_object;
  bool settled = false;  // every part came to rest inside the bin before max_simulated_time
  int lost = 0;          // parts that were not inside the bin when the time ran out
  // Times a part came to rest outside the bin (e.g. across a wall) and was dropped again.
  int redrops = 0;
  int layers = 0;               // how many times parts were released
  double simulated_time = 0.0;  // seconds
  long steps = 0;               // Bullet steps of time_step / substeps
  int convex_pieces = 0;        // in the part's collision shape
};

// Drops `objects` copies of `part` (a closed triangle mesh with outward normals, metres; the model
// frame may be anywhere, the poses place it) into the bin and simulates until the pile settles or
// max_simulated_time runs out. The orientations, positions and release heights are random, drawn
// from `seed`. A part that comes to rest outside the bin is taken out and dropped again; one still
// outside when the time runs out is left out of the result and counted in `lost`, never returned.
// Throws core::Error on bad params or bin, a mesh with bad indices or no enclosed volume (empty,
// inside out), or a part too large to be released between the walls in every orientation. A mesh
// with holes is not detected: its collision shape is then the decomposition of what its surface
// appears to enclose.
PhysicsPile simulatePile(const io::TriangleMesh& part, int objects, const BinInterior& bin, const PhysicsParams& params,
                         uint64_t seed);

// How the pile re-settled after a part was taken out (PhysicsBin::remove).
struct SettleResult {
  bool settled = false;         // every remaining part came to rest within max_resettle_time
  double simulated_time = 0.0;  // seconds, this call
  long steps = 0;               // Bullet steps of time_step / substeps, this call
  // Parts that ended outside the bin (over a wall, off the world) and were taken out too: their
  // indices into poses() as it was before the call (the removed part itself is not among them).
  std::vector<int> escaped;
};

// A pile that lives on: parts dropped into the bin stay in one Bullet world, and taking one out
// lets the rest slide and fall into their new places. Deterministic: the same seed and the same
// sequence of calls give bit-identical poses on the same build. Not copyable; one thread at a time
// (calls on different PhysicsBin objects may run concurrently, as simulatePile's do).
class PhysicsBin {
 public:
  // Builds the part's collision shape (0.03-0.15 s for the built-in parts). Throws
  // core::Error on bad params or bin, a bad mesh, or a part too large for the bin, as
  // simulatePile does.
  PhysicsBin(const io::TriangleMesh& part, const BinInterior& bin, const PhysicsParams& params, uint64_t seed);
  ~PhysicsBin();
  PhysicsBin(PhysicsBin&&) noexcept;
  PhysicsBin& operator=(PhysicsBin&&) noexcept;
  PhysicsBin(const PhysicsBin&) = delete;
  PhysicsBin& operator=(const PhysicsBin&) = delete;

  // Drops `objects` more parts onto whatever lies in the bin, exactly as simulatePile does
  // (simulatePile is a fresh PhysicsBin's first drop). The time limit max_simulated_time and
  // the counts (settled, lost, redrops, layers, time, steps) are this call's; T_bin_object lists
  // every part now in the bin, as poses() does. Throws core::Error when objects < 0.
  PhysicsPile drop(int objects);

  // T_bin_object of every part in the bin, in the order the parts were added (the order of their
  // last release), removed ones left out.
  std::vector<Eigen::Isometry3d> poses() const;
  int size() const;

  // Takes part `index` (into poses()) out of the world, wakes every other part (resting parts
  // sleep, and Bullet would leave one hanging in the air when its support goes), steps until
  // everything is at rest again or max_resettle_time runs out, then takes out parts that ended
  // outside the bin. Throws core::Error on an index outside [0, size()).
  SettleResult remove(int index);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace binpick::simulation
