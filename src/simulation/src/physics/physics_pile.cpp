// simulatePile: drop layers of parts into the bin until all have come to rest inside it.
#include "binpick/simulation/physics_pile.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "../random.hpp"
#include "binpick/io/error.hpp"
#include "mass_properties.hpp"
#include "part_shape.hpp"
#include "pile_simulation.hpp"
#include "release_layout.hpp"

namespace binpick::sim {
namespace {

// The release poses' random stream under the seed (generatePile draws its sensor noise from 1).
constexpr uint32_t kReleaseStream = 2;
// Gap kept at release between a part's footprint and the inner walls, beyond the collision margin.
constexpr double kWallClearance = 0.0005;  // metres

void requirePositive(double value, const char* field) {
  if (std::isfinite(value) && value > 0.0) return;
  std::ostringstream message;
  message << "simulatePile: " << field << " must be positive (got " << value << ")";
  throw Error(message.str());
}

void requireValidInputs(const TriangleMesh& part, int objects, const BinInterior& bin,
                        const PhysicsParams& params) {
  params.validate();
  if (objects < 0) {
    throw Error("simulatePile: objects must be >= 0 (got " + std::to_string(objects) + ")");
  }
  requirePositive(bin.length, "bin.length");
  requirePositive(bin.width, "bin.width");
  requirePositive(bin.wall_height, "bin.wall_height");
  if (part.empty()) throw Error("simulatePile: the part mesh has no triangles");
  validateMesh(part, "simulatePile part");
}

// Released in any orientation, the part must fit between the walls: its extent in any direction is
// at most the diameter of the sphere around its centroid that holds it. Returns the clearance
// kept from the walls at release.
double requireFitsInBin(const TriangleMesh& part, const BinInterior& bin,
                        const PhysicsParams& params) {
  const detail::MassProperties mass = detail::massProperties(part);
  if (!(mass.volume > 0.0)) {
    throw Error("simulatePile: the part mesh encloses no volume (it must be closed, normals out)");
  }
  const double clearance = params.collision_margin + kWallClearance;
  const Eigen::Vector3d& centroid = mass.centroid;
  double radius = 0.0;
  for (const auto& v : part.vertices) radius = std::max(radius, (v.cast<double>() - centroid).norm());
  const double diameter = 2.0 * radius + 2.0 * clearance;
  if (diameter > std::min(bin.length, bin.width)) {
    std::ostringstream message;
    message << "simulatePile: the part (" << diameter
            << " m across in its worst orientation) does not fit in a bin of " << bin.length
            << " x " << bin.width << " m";
    throw Error(message.str());
  }
  return clearance;
}

}  // namespace

PhysicsPile simulatePile(const TriangleMesh& part, int objects, const BinInterior& bin,
                         const PhysicsParams& params, uint64_t seed) {
  requireValidInputs(part, objects, bin, params);
  const double clearance = requireFitsInBin(part, bin, params);
  const detail::PartShape shape(part, params);
  detail::PileSimulation simulation(shape, bin, params);
  detail::Rng rng = detail::makeRng(seed, kReleaseStream);

  PhysicsPile result;
  result.convex_pieces = shape.pieces();
  int waiting = objects;
  bool settled = true;
  while (waiting > 0) {
    const auto layer = detail::releaseLayer(waiting, simulation.pileTop(), shape.extremePoints(),
                                            bin, params, clearance, rng);
    simulation.release(layer);
    waiting -= static_cast<int>(layer.size());
    ++result.layers;
    settled = simulation.settle();
    const int escaped = simulation.removeEscaped();  // never kept, settled or not
    if (!settled) {
      result.lost = waiting + escaped;
      break;
    }
    waiting += escaped;
    result.redrops += escaped;
  }
  result.settled = settled;
  result.T_bin_object = simulation.poses();
  result.simulated_time = simulation.simulatedTime();
  result.steps = simulation.steps();
  return result;
}

}  // namespace binpick::sim
