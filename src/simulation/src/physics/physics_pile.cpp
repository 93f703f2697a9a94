// PhysicsBin: drop layers of parts into the bin until all have come to rest inside it, take parts
// out and let the rest re-settle. simulatePile is a fresh PhysicsBin's first drop.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "../random.hpp"
#include "binpick/core/error.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "mass_properties.hpp"
#include "part_shape.hpp"
#include "pile_simulation.hpp"
#include "release_layout.hpp"

namespace binpick::simulation {
namespace {

// The release poses' random stream under the seed (generatePile draws its sensor noise from 1).
constexpr uint32_t kReleaseStream = 2;
// Gap kept at release between a part's footprint and the inner walls, beyond the collision margin.
constexpr double kWallClearance = 0.0005;  // metres

void requirePositive(double value, const char* field) {
  if (std::isfinite(value) && value > 0.0) return;
  std::ostringstream message;
  message << "simulatePile: " << field << " must be positive (got " << value << ")";
  throw core::Error(message.str());
}

void requireObjects(int objects) {
  if (objects < 0) {
    throw core::Error("simulatePile: objects must be >= 0 (got " + std::to_string(objects) + ")");
  }
}

void requireValidInputs(const io::TriangleMesh& part, const BinInterior& bin, const PhysicsParams& params) {
  params.validate();
  requirePositive(bin.length, "bin.length");
  requirePositive(bin.width, "bin.width");
  requirePositive(bin.wall_height, "bin.wall_height");
  if (part.empty()) throw core::Error("simulatePile: the part mesh has no triangles");
  io::validateMesh(part, "simulatePile part");
}

// Released in any orientation, the part must fit between the walls: its extent in any direction is
// at most the diameter of the sphere around its centroid that holds it. Returns the clearance
// kept from the walls at release.
double requireFitsInBin(const io::TriangleMesh& part, const BinInterior& bin, const PhysicsParams& params) {
  const detail::MassProperties mass = detail::massProperties(part);
  if (!(mass.volume > 0.0)) {
    throw core::Error("simulatePile: the part mesh encloses no volume (it must be closed, normals out)");
  }
  const double clearance = params.collision_margin + kWallClearance;
  const Eigen::Vector3d& centroid = mass.centroid;
  double radius = 0.0;
  for (const auto& v : part.vertices) radius = std::max(radius, (v.cast<double>() - centroid).norm());
  const double diameter = 2.0 * radius + 2.0 * clearance;
  if (diameter > std::min(bin.length, bin.width)) {
    std::ostringstream message;
    message << "simulatePile: the part (" << diameter << " m across in its worst orientation) does not fit in a bin of "
            << bin.length << " x " << bin.width << " m";
    throw core::Error(message.str());
  }
  return clearance;
}

// Validates everything about the inputs before any work is done; returns the clearance kept from
// the walls at release.
double validatedClearance(const io::TriangleMesh& part, const BinInterior& bin, const PhysicsParams& params) {
  requireValidInputs(part, bin, params);
  return requireFitsInBin(part, bin, params);
}

// Time limits in whole steps, so that no rounding of a running sum decides when to stop.
int framesIn(double seconds, const PhysicsParams& params) {
  return static_cast<int>(std::floor(seconds / params.time_step));
}

}  // namespace

struct PhysicsBin::Impl {
  Impl(const io::TriangleMesh& part, const BinInterior& bin_interior, const PhysicsParams& physics, uint64_t seed)
      : interior(bin_interior),
        params(physics),
        clearance(validatedClearance(part, interior, params)),
        shape(part, params),
        simulation(shape, interior, params),
        rng(detail::makeRng(seed, kReleaseStream)) {}

  BinInterior interior;
  PhysicsParams params;
  double clearance;  // kept from the walls at release
  detail::PartShape shape;
  detail::PileSimulation simulation;  // refers to `shape`: declared after it
  detail::Rng rng;
};

PhysicsBin::PhysicsBin(const io::TriangleMesh& part, const BinInterior& bin, const PhysicsParams& params, uint64_t seed)
    : impl_(std::make_unique<Impl>(part, bin, params, seed)) {}

PhysicsBin::~PhysicsBin() = default;
PhysicsBin::PhysicsBin(PhysicsBin&&) noexcept = default;
PhysicsBin& PhysicsBin::operator=(PhysicsBin&&) noexcept = default;

// Layer after layer until every part lies inside the bin; parts that came to rest outside it are
// dropped again, as long as time remains.
PhysicsPile PhysicsBin::drop(int objects) {
  requireObjects(objects);
  Impl& bin = *impl_;
  detail::PileSimulation& simulation = bin.simulation;
  const int first_frame = simulation.frames();
  const int frame_limit = first_frame + framesIn(bin.params.max_simulated_time, bin.params);

  PhysicsPile result;
  result.convex_pieces = bin.shape.pieces();
  int waiting = objects;
  bool settled = true;
  while (waiting > 0) {
    const auto layer = detail::releaseLayer(waiting, simulation.pileTop(), bin.shape.extremePoints(), bin.interior,
                                            bin.params, bin.clearance, bin.rng);
    simulation.release(layer);
    waiting -= static_cast<int>(layer.size());
    ++result.layers;
    settled = simulation.settle(frame_limit);
    // Never kept, settled or not.
    const int escaped = static_cast<int>(simulation.removeEscaped().size());
    if (!settled) {
      result.lost = waiting + escaped;
      break;
    }
    waiting += escaped;
    result.redrops += escaped;
  }
  const int frames = simulation.frames() - first_frame;
  result.settled = settled;
  result.T_bin_object = simulation.poses();
  result.simulated_time = frames * bin.params.time_step;
  result.steps = static_cast<long>(frames) * bin.params.substeps;
  return result;
}

std::vector<Eigen::Isometry3d> PhysicsBin::poses() const { return impl_->simulation.poses(); }

int PhysicsBin::size() const { return impl_->simulation.size(); }

SettleResult PhysicsBin::remove(int index) {
  detail::PileSimulation& simulation = impl_->simulation;
  if (index < 0 || index >= simulation.size()) {
    throw core::Error("PhysicsBin::remove: index " + std::to_string(index) + " is not in [0, " +
                      std::to_string(simulation.size()) + ")");
  }
  const std::vector<int> serials_before = simulation.serials();
  const int first_frame = simulation.frames();
  simulation.removeAt(index);

  SettleResult result;
  result.settled = simulation.settle(first_frame + framesIn(impl_->params.max_resettle_time, impl_->params));
  for (const int serial : simulation.removeEscaped()) {
    const auto at = std::find(serials_before.begin(), serials_before.end(), serial);
    result.escaped.push_back(static_cast<int>(at - serials_before.begin()));
  }
  std::sort(result.escaped.begin(), result.escaped.end());
  const int frames = simulation.frames() - first_frame;
  result.simulated_time = frames * impl_->params.time_step;
  result.steps = static_cast<long>(frames) * impl_->params.substeps;
  return result;
}

PhysicsPile simulatePile(const io::TriangleMesh& part, int objects, const BinInterior& bin, const PhysicsParams& params,
                         uint64_t seed) {
  requireObjects(objects);
  return PhysicsBin(part, bin, params, seed).drop(objects);
}

}  // namespace binpick::simulation

// PhysicsParams::validate: every field checked, the message names the first bad one.
namespace binpick::simulation {
namespace {

class Checker {
 public:
  explicit Checker(const std::string& name) : name_(name) {}

  void require(bool ok, const char* field, const char* rule, double value) const {
    core::requireField(ok, name_, field, rule, value);
  }

 private:
  const std::string& name_;
};

bool finiteIn(double value, double low, double high) { return std::isfinite(value) && value >= low && value <= high; }

bool positiveUpTo(double value, double high) { return std::isfinite(value) && value > 0.0 && value <= high; }

// Upper limits keep a typo (a length in millimetres, a time in milliseconds) from turning into a
// run that never ends or a grid that exhausts memory.
constexpr double kMaxDropHeight = 10.0;  // metres
constexpr double kMaxFriction = 10.0;    // Bullet clamps combined friction there
constexpr double kMaxTimeStep = 0.1;     // seconds
constexpr int kMaxSubsteps = 1000;
constexpr double kMaxSimulatedTime = 3600.0;  // seconds
constexpr double kMaxSmallLength = 0.1;       // metres: tolerances, margins, lever arms
constexpr int kMaxPieces = 1024;

}  // namespace

void PhysicsParams::validate(const std::string& name) const {
  const Checker check(name);
  check.require(finiteIn(drop_height_min, 0.0, kMaxDropHeight), "drop_height_min", "in [0, 10]", drop_height_min);
  check.require(finiteIn(drop_height_max, drop_height_min, kMaxDropHeight), "drop_height_max",
                "in [drop_height_min, 10]", drop_height_max);
  check.require(finiteIn(friction, 0.0, kMaxFriction), "friction", "in [0, 10]", friction);
  check.require(finiteIn(restitution, 0.0, 1.0), "restitution", "in [0, 1]", restitution);
  check.require(finiteIn(rolling_resistance, 0.0, kMaxSmallLength), "rolling_resistance", "in [0, 0.1]",
                rolling_resistance);
  check.require(positiveUpTo(time_step, kMaxTimeStep), "time_step", "in (0, 0.1]", time_step);
  check.require(substeps >= 1 && substeps <= kMaxSubsteps, "substeps", "in [1, 1000]", substeps);
  check.require(positiveUpTo(max_simulated_time, kMaxSimulatedTime), "max_simulated_time", "in (0, 3600]",
                max_simulated_time);
  check.require(positiveUpTo(max_resettle_time, kMaxSimulatedTime), "max_resettle_time", "in (0, 3600]",
                max_resettle_time);
  check.require(std::isfinite(settle_linear_velocity) && settle_linear_velocity > 0.0, "settle_linear_velocity",
                "positive", settle_linear_velocity);
  check.require(std::isfinite(settle_angular_velocity) && settle_angular_velocity > 0.0, "settle_angular_velocity",
                "positive", settle_angular_velocity);
  check.require(finiteIn(settle_time, 0.0, max_simulated_time), "settle_time", "in [0, max_simulated_time]",
                settle_time);
  check.require(positiveUpTo(decomposition_tolerance, kMaxSmallLength), "decomposition_tolerance", "in (0, 0.1]",
                decomposition_tolerance);
  check.require(max_convex_pieces >= 1 && max_convex_pieces <= kMaxPieces, "max_convex_pieces", "in [1, 1024]",
                max_convex_pieces);
  check.require(positiveUpTo(collision_margin, kMaxSmallLength), "collision_margin", "in (0, 0.1]", collision_margin);
}

}  // namespace binpick::simulation
