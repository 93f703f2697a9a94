#include "bin.hpp"

#include <array>

namespace binpick::sim::detail {
namespace {

// An axis-aligned closed box with outward-facing triangles, appended to `mesh`.
void appendBox(TriangleMesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  const int base = static_cast<int>(mesh.vertices.size());
  // Corner k has x from bit 0, y from bit 1, z from bit 2 (0 = lo, 1 = hi).
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                               (k & 4) ? hi.z() : lo.z());
  }
  // Each face as a counter-clockwise quad seen from outside.
  const std::array<std::array<int, 4>, 6> faces{{
      {0, 2, 3, 1},  // z = lo
      {4, 5, 7, 6},  // z = hi
      {0, 1, 5, 4},  // y = lo
      {2, 6, 7, 3},  // y = hi
      {0, 4, 6, 2},  // x = lo
      {1, 3, 7, 5},  // x = hi
  }};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(base + f[0], base + f[1], base + f[2]);
    mesh.triangles.emplace_back(base + f[0], base + f[2], base + f[3]);
  }
}

}  // namespace

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
