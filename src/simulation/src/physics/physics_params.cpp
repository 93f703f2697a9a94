// PhysicsParams::validate: every field checked, the message names the first bad one.
#include <cmath>

#include "binpick/io/error.hpp"
#include "binpick/simulation/physics_pile.hpp"

namespace binpick::sim {
namespace {

class Checker {
 public:
  explicit Checker(const std::string& name) : name_(name) {}

  void require(bool ok, const char* field, const char* rule, double value) const {
    requireField(ok, name_, field, rule, value);
  }

 private:
  const std::string& name_;
};

bool finiteIn(double value, double low, double high) {
  return std::isfinite(value) && value >= low && value <= high;
}

bool positiveUpTo(double value, double high) {
  return std::isfinite(value) && value > 0.0 && value <= high;
}

// Upper limits keep a typo (a length in millimetres, a time in milliseconds) from turning into a
// run that never ends or a grid that exhausts memory.
constexpr double kMaxDropHeight = 10.0;   // metres
constexpr double kMaxFriction = 10.0;     // Bullet clamps combined friction there
constexpr double kMaxTimeStep = 0.1;      // seconds
constexpr int kMaxSubsteps = 1000;
constexpr double kMaxSimulatedTime = 3600.0;  // seconds
constexpr double kMaxSmallLength = 0.1;   // metres: tolerances, margins, lever arms
constexpr int kMaxPieces = 1024;

}  // namespace

void PhysicsParams::validate(const std::string& name) const {
  const Checker check(name);
  check.require(finiteIn(drop_height_min, 0.0, kMaxDropHeight), "drop_height_min", "in [0, 10]",
                drop_height_min);
  check.require(finiteIn(drop_height_max, drop_height_min, kMaxDropHeight), "drop_height_max",
                "in [drop_height_min, 10]", drop_height_max);
  check.require(finiteIn(friction, 0.0, kMaxFriction), "friction", "in [0, 10]", friction);
  check.require(finiteIn(restitution, 0.0, 1.0), "restitution", "in [0, 1]", restitution);
  check.require(finiteIn(rolling_resistance, 0.0, kMaxSmallLength), "rolling_resistance",
                "in [0, 0.1]", rolling_resistance);
  check.require(positiveUpTo(time_step, kMaxTimeStep), "time_step", "in (0, 0.1]", time_step);
  check.require(substeps >= 1 && substeps <= kMaxSubsteps, "substeps", "in [1, 1000]", substeps);
  check.require(positiveUpTo(max_simulated_time, kMaxSimulatedTime), "max_simulated_time",
                "in (0, 3600]", max_simulated_time);
  check.require(positiveUpTo(max_resettle_time, kMaxSimulatedTime), "max_resettle_time",
                "in (0, 3600]", max_resettle_time);
  check.require(std::isfinite(settle_linear_velocity) && settle_linear_velocity > 0.0,
                "settle_linear_velocity", "positive", settle_linear_velocity);
  check.require(std::isfinite(settle_angular_velocity) && settle_angular_velocity > 0.0,
                "settle_angular_velocity", "positive", settle_angular_velocity);
  check.require(finiteIn(settle_time, 0.0, max_simulated_time), "settle_time",
                "in [0, max_simulated_time]", settle_time);
  check.require(positiveUpTo(decomposition_tolerance, kMaxSmallLength), "decomposition_tolerance",
                "in (0, 0.1]", decomposition_tolerance);
  check.require(max_convex_pieces >= 1 && max_convex_pieces <= kMaxPieces, "max_convex_pieces",
                "in [1, 1024]", max_convex_pieces);
  check.require(positiveUpTo(collision_margin, kMaxSmallLength), "collision_margin", "in (0, 0.1]",
                collision_margin);
}

}  // namespace binpick::sim
