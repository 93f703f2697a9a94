// SensorGeometryParams::validate: every field checked, the message names the first bad one.
#include <cmath>

#include "binpick/io/error.hpp"
#include "binpick/simulation/sensor_geometry.hpp"

namespace binpick::sim {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  requireField(ok, "SensorGeometryParams", field, rule, value);
}

constexpr int kMaxThreads = 1024;
// An offset this large would visibly move shadow edges; anything beyond it is a unit mistake.
constexpr double kMaxShadowRayOffset = 0.01;

}  // namespace

void SensorGeometryParams::validate() const {
  require(threads >= 0 && threads <= kMaxThreads, "threads", "in [0, 1024]", threads);
  require(std::isfinite(shadow_ray_offset) && shadow_ray_offset >= 0.0 &&
              shadow_ray_offset <= kMaxShadowRayOffset,
          "shadow_ray_offset", "in [0, 0.01] metres", shadow_ray_offset);
}

}  // namespace binpick::sim
