// Area-proportional sampling of a mesh's surface.
#include "binpick/io/mesh_surface.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace binpick::io {
namespace {

Eigen::Vector3f triangleNormalTimesTwoArea(const TriangleMesh& mesh, const Eigen::Vector3i& t) {
  const Eigen::Vector3f& a = mesh.vertices[t[0]];
  return (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
}

}  // namespace

double surfaceArea(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += 0.5 * triangleNormalTimesTwoArea(mesh, t).norm();
  return area;
}

SurfaceSamples sampleSurface(const TriangleMesh& mesh, std::size_t count, uint64_t seed) {
  std::vector<double> cumulative_area;
  cumulative_area.reserve(mesh.triangles.size());
  double total = 0.0;
  for (const auto& t : mesh.triangles) {
    total += 0.5 * triangleNormalTimesTwoArea(mesh, t).norm();
    cumulative_area.push_back(total);
  }
  SurfaceSamples samples;
  if (total <= 0.0 || count == 0) return samples;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  samples.points.reserve(count);
  samples.face_normals.reserve(count);
  for (std::size_t s = 0; s < count; ++s) {
    const double pick = uniform(rng) * total;
    const std::size_t face = std::min<std::size_t>(
        std::lower_bound(cumulative_area.begin(), cumulative_area.end(), pick) - cumulative_area.begin(),
        mesh.triangles.size() - 1);
    const Eigen::Vector3i& t = mesh.triangles[face];
    const Eigen::Vector3f n2a = triangleNormalTimesTwoArea(mesh, t);
    if (n2a.norm() <= 0.0f) continue;
    // Uniform point in a triangle from two uniforms (square-root warp).
    const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
    const Eigen::Vector3f p = static_cast<float>(1.0 - r1) * mesh.vertices[t[0]] +
                              static_cast<float>(r1 * (1.0 - r2)) * mesh.vertices[t[1]] +
                              static_cast<float>(r1 * r2) * mesh.vertices[t[2]];
    samples.points.push_back(p);
    samples.face_normals.push_back(n2a.normalized());
  }
  return samples;
}

}  // namespace binpick::io
