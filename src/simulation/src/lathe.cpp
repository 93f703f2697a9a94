// makeLathe: a profile polygon in the (r, z) half-plane revolved about z into a closed,
// outward-oriented triangle mesh.
#include <cmath>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "polygon.hpp"

namespace binpick::simulation {
namespace {

constexpr double kPi = 3.14159265358979323846;

detail::Polygon validatedProfile(const std::vector<Eigen::Vector2d>& profile, int segments) {
  if (segments < 3) {
    throw core::Error("makeLathe: needs at least 3 segments, got " + std::to_string(segments));
  }
  for (const auto& p : profile) {
    if (p.allFinite() && p.x() < 0.0) {
      throw core::Error("makeLathe: the profile has a point with r < 0 (r = " + std::to_string(p.x()) + ")");
    }
  }
  try {
    return detail::cleanSimplePolygon(profile);  // counter-clockwise in (r, z) from here on
  } catch (const core::Error& e) {
    throw core::Error(std::string("makeLathe: invalid profile: ") + e.what());
  }
}

}  // namespace

io::TriangleMesh makeLathe(const std::vector<Eigen::Vector2d>& profile, int segments) {
  const detail::Polygon polygon = validatedProfile(profile, segments);
  const int n = static_cast<int>(polygon.size());
  // Vertex layout: for each profile point, one vertex if it is on the axis, else a ring of
  // `segments` vertices at angles 2 pi k / segments. first[i] is the index of point i's first.
  std::vector<int> first(n);
  std::vector<bool> on_axis(n);
  io::TriangleMesh mesh;
  for (int i = 0; i < n; ++i) {
    const double r = polygon[i].x(), z = polygon[i].y();
    first[i] = static_cast<int>(mesh.vertices.size());
    on_axis[i] = r == 0.0;
    const int count = on_axis[i] ? 1 : segments;
    for (int k = 0; k < count; ++k) {
      const double angle = 2.0 * kPi * k / segments;
      mesh.vertices.emplace_back(Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z).cast<float>());
    }
  }
  const auto at = [&](int i, int k) { return on_axis[i] ? first[i] : first[i] + k % segments; };
  // A counter-clockwise (r, z) profile has the solid on the left of each edge i -> j, so the
  // outward normal is to the right; with the ring advancing counter-clockwise about +z, the
  // windings (i_k, j_k+1, j_k) and (i_k, i_k+1, j_k+1) face outwards.
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if (on_axis[i] && on_axis[j]) continue;  // an edge on the axis sweeps no surface
    for (int k = 0; k < segments; ++k) {
      if (!on_axis[j]) mesh.triangles.emplace_back(at(i, k), at(j, k + 1), at(j, k));
      if (!on_axis[i]) mesh.triangles.emplace_back(at(i, k), at(i, k + 1), at(j, k + 1));
    }
  }
  return mesh;
}

}  // namespace binpick::simulation
