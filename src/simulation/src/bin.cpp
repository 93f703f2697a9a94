#include "bin.hpp"

#include "mesh_geometry.hpp"

namespace binpick::sim::detail {

TriangleMesh makeBinMesh(double length, double width, double wall_height) {
  const float hl = static_cast<float>(0.5 * length), hw = static_cast<float>(0.5 * width);
  const float t = static_cast<float>(kBinWallThickness), h = static_cast<float>(wall_height);
  const float floor_bottom = static_cast<float>(-kBinFloorThickness);
  TriangleMesh mesh;
  appendBox(mesh, {-hl - t, -hw - t, floor_bottom}, {hl + t, hw + t, 0.0f});
  // Walls along y span the full outer width so that the corners are closed.
  appendBox(mesh, {-hl - t, -hw - t, 0.0f}, {-hl, hw + t, h});
  appendBox(mesh, {hl, -hw - t, 0.0f}, {hl + t, hw + t, h});
  appendBox(mesh, {-hl, -hw - t, 0.0f}, {hl, -hw, h});
  appendBox(mesh, {-hl, hw, 0.0f}, {hl, hw + t, h});
  return mesh;
}

}  // namespace binpick::sim::detail
