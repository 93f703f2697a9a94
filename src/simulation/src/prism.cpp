// makePrism: a profile polygon extruded along z into a closed, outward-oriented triangle mesh.
#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "polygon.hpp"

namespace binpick::simulation {
namespace {

// Vertex layout: the n profile corners at z = -thickness/2 (indices 0..n-1), then the same
// corners at z = +thickness/2 (indices n..2n-1).
std::vector<Eigen::Vector3f> extrudedVertices(const detail::Polygon& polygon, double thickness) {
  std::vector<Eigen::Vector3f> vertices;
  vertices.reserve(2 * polygon.size());
  for (const double z : {-0.5 * thickness, 0.5 * thickness}) {
    for (const auto& p : polygon) vertices.emplace_back(Eigen::Vector3d(p.x(), p.y(), z).cast<float>());
  }
  return vertices;
}

// Caps: the top keeps the counter-clockwise winding (normal +z); the bottom is flipped (-z).
void addCaps(const detail::Polygon& polygon, std::vector<Eigen::Vector3i>& triangles) {
  const int n = static_cast<int>(polygon.size());
  for (const auto& t : detail::triangulateByEarClipping(polygon)) {
    triangles.emplace_back(n + t[0], n + t[1], n + t[2]);
    triangles.emplace_back(t[0], t[2], t[1]);
  }
}

// Sides: one quad per profile edge i->j. With a counter-clockwise profile the inside is on the
// left of the edge, so (bottom_i, bottom_j, top_j) has its normal to the right: outwards.
void addSides(int n, std::vector<Eigen::Vector3i>& triangles) {
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const int bottom_i = i, bottom_j = j, top_i = n + i, top_j = n + j;
    triangles.emplace_back(bottom_i, bottom_j, top_j);
    triangles.emplace_back(bottom_i, top_j, top_i);
  }
}

}  // namespace

io::TriangleMesh makePrism(const std::vector<Eigen::Vector2d>& profile, double thickness) {
  if (!std::isfinite(thickness) || thickness <= 0.0) {
    throw core::Error("makePrism: thickness must be positive, got " + std::to_string(thickness));
  }
  const detail::Polygon polygon = detail::cleanSimplePolygon(profile);
  io::TriangleMesh mesh;
  mesh.vertices = extrudedVertices(polygon, thickness);
  mesh.triangles.reserve(4 * polygon.size());
  addCaps(polygon, mesh.triangles);
  addSides(static_cast<int>(polygon.size()), mesh.triangles);
  return mesh;
}

}  // namespace binpick::simulation
