#include "mesh_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace binpick::simulation::detail {
namespace {

struct Corners {
  Eigen::Vector3d a, b, c;
};

Corners corners(const io::TriangleMesh& mesh, const Eigen::Vector3i& triangle) {
  return {mesh.vertices[triangle[0]].cast<double>(), mesh.vertices[triangle[1]].cast<double>(),
          mesh.vertices[triangle[2]].cast<double>()};
}

// Samples in rows parallel to the longest edge, from that edge up to the opposite corner, rows and
// samples along a row at most `step` apart. The opposite corner projects inside the longest edge,
// so each row spans the triangle's whole cross-section up to the next row: any point has a sample
// within one step across and half a step along. The count grows with the area, not with the
// square of the longest edge, so long slivers stay cheap. Includes the three corners.
void appendTriangleSamples(const Corners& t, double step, std::vector<Eigen::Vector3f>& out) {
  const std::array<Eigen::Vector3d, 3> corner{t.a, t.b, t.c};
  int longest = 0;  // the edge corner[longest] -> corner[longest + 1]
  for (int k = 1; k < 3; ++k) {
    if ((corner[(k + 1) % 3] - corner[k]).norm() > (corner[(longest + 1) % 3] - corner[longest]).norm()) {
      longest = k;
    }
  }
  const Eigen::Vector3d& a = corner[longest];
  const Eigen::Vector3d& b = corner[(longest + 1) % 3];
  const Eigen::Vector3d& c = corner[(longest + 2) % 3];
  const double base = (b - a).norm();
  const double height = base > 0.0 ? (b - a).cross(c - a).norm() / base : 0.0;
  const int rows = std::max(1, static_cast<int>(std::ceil(height / step)));
  for (int k = 0; k <= rows; ++k) {
    const double up = static_cast<double>(k) / rows;
    const Eigen::Vector3d left = a + up * (c - a), right = b + up * (c - b);
    const int intervals = std::max(1, static_cast<int>(std::ceil((right - left).norm() / step)));
    for (int j = 0; j <= intervals; ++j) {
      const double along = static_cast<double>(j) / intervals;
      out.emplace_back((left + along * (right - left)).cast<float>());
    }
  }
}

}  // namespace

double signedVolume(const io::TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const auto& triangle : mesh.triangles) {
    const Corners t = corners(mesh, triangle);
    six_volume += t.a.dot(t.b.cross(t.c));
  }
  return six_volume / 6.0;
}

Eigen::Vector3d volumeCentroid(const io::TriangleMesh& mesh) {
  // Each tetrahedron (origin, a, b, c) has its centroid at (a + b + c) / 4.
  double six_volume = 0.0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (const auto& triangle : mesh.triangles) {
    const Corners t = corners(mesh, triangle);
    const double v = t.a.dot(t.b.cross(t.c));
    six_volume += v;
    weighted += v * (t.a + t.b + t.c) / 4.0;
  }
  return six_volume != 0.0 ? Eigen::Vector3d(weighted / six_volume) : Eigen::Vector3d::Zero();
}

io::TriangleMesh translated(const io::TriangleMesh& mesh, const Eigen::Vector3d& offset) {
  io::TriangleMesh moved = mesh;
  for (auto& v : moved.vertices) v = (v.cast<double>() + offset).cast<float>();
  return moved;
}

void appendBox(io::TriangleMesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  const int base = static_cast<int>(mesh.vertices.size());
  // Corner k has x from bit 0, y from bit 1, z from bit 2 (0 = lo, 1 = hi).
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
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

std::vector<Eigen::Vector3f> surfaceSamples(const io::TriangleMesh& mesh, double coverage_radius) {
  // Rows and samples `step` apart leave every point within sqrt(step^2 + (step/2)^2) of a sample.
  const double step = coverage_radius / std::sqrt(1.25);
  std::vector<Eigen::Vector3f> samples;
  for (const auto& triangle : mesh.triangles) appendTriangleSamples(corners(mesh, triangle), step, samples);
  return samples;
}

}  // namespace binpick::simulation::detail
