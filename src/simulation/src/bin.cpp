#include "bin.hpp"

#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "mesh_geometry.hpp"

namespace binpick::simulation::detail {

io::TriangleMesh makeBinMesh(double length, double width, double wall_height) {
  const float hl = static_cast<float>(0.5 * length), hw = static_cast<float>(0.5 * width);
  const float t = static_cast<float>(kBinWallThickness), h = static_cast<float>(wall_height);
  const float floor_bottom = static_cast<float>(-kBinFloorThickness);
  io::TriangleMesh mesh;
  appendBox(mesh, {-hl - t, -hw - t, floor_bottom}, {hl + t, hw + t, 0.0f});
  // Walls along y span the full outer width so that the corners are closed.
  appendBox(mesh, {-hl - t, -hw - t, 0.0f}, {-hl, hw + t, h});
  appendBox(mesh, {hl, -hw - t, 0.0f}, {hl + t, hw + t, h});
  appendBox(mesh, {-hl, -hw - t, 0.0f}, {hl, -hw, h});
  appendBox(mesh, {-hl, hw, 0.0f}, {hl, hw + t, h});
  return mesh;
}

}  // namespace binpick::simulation::detail

namespace binpick::simulation {

io::TriangleMesh binMesh(const BinInterior& bin) {
  for (const double size : {bin.length, bin.width, bin.wall_height}) {
    if (!(std::isfinite(size) && size > 0.0)) {
      throw core::Error("binMesh: the bin's length, width and wall_height must be positive and finite");
    }
  }
  return detail::makeBinMesh(bin.length, bin.width, bin.wall_height);
}

}  // namespace binpick::simulation
