#pragma once
// Independent geometry checks for the simulation tests (deliberately not sharing code with the
// library, so that a bug there cannot hide itself here).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::simulation::test {

// Empty when every undirected edge is used by exactly two triangles in opposite directions.
inline std::string closedManifoldProblem(const io::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1)
      return "edge " + std::to_string(edge.first) + "->" + std::to_string(edge.second) + " used " +
             std::to_string(count) + " times in the same direction";
    if (directed.count({edge.second, edge.first}) == 0) {
      return "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " has no opposite";
    }
  }
  return {};
}

inline double signedVolume(const io::TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

inline Eigen::AlignedBox3d bounds(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  return box;
}

// A mesh placed in some frame, vertices in double.
struct PlacedMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  Eigen::AlignedBox3d box;
};

inline PlacedMesh place(const io::TriangleMesh& mesh, const Eigen::Isometry3d& pose) {
  PlacedMesh placed;
  for (const auto& v : mesh.vertices) placed.vertices.push_back(pose * v.cast<double>());
  placed.triangles = mesh.triangles;
  placed.box = bounds(placed.vertices);
  return placed;
}

// Möller-Trumbore; the ray parameter of the hit, or nullopt-like NaN when it misses.
inline double rayTriangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = dir.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-18) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3d s = origin - a;
  const double u = s.dot(p) / det;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = dir.dot(q) / det;
  if (u < 0.0 || v < 0.0 || u + v > 1.0) return std::numeric_limits<double>::quiet_NaN();
  return e2.dot(q) / det;
}

// Parity of crossings along a skew ray: a closed mesh is entered and left an even number of times.
inline bool insideMesh(const PlacedMesh& mesh, const Eigen::Vector3d& point) {
  if (!mesh.box.contains(point)) return false;
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3141, 0.5926, 0.7358).normalized();
  int crossings = 0;
  for (const auto& t : mesh.triangles) {
    const double hit = rayTriangle(point, dir, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    if (hit > 0.0) ++crossings;
  }
  return crossings % 2 == 1;
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
inline Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

inline double distanceToSurface(const PlacedMesh& mesh, const Eigen::Vector3d& point) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d q = closestOnTriangle(point, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    best = std::min(best, (q - point).norm());
  }
  return best;
}

// Vertices plus a barycentric grid of `steps` per edge on every triangle.
inline std::vector<Eigen::Vector3d> surfacePoints(const PlacedMesh& mesh, int steps) {
  std::vector<Eigen::Vector3d> points = mesh.vertices;
  for (const auto& t : mesh.triangles) {
    const auto &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    for (int i = 0; i <= steps; ++i) {
      for (int j = 0; i + j <= steps; ++j) {
        points.push_back(a + (b - a) * (double(i) / steps) + (c - a) * (double(j) / steps));
      }
    }
  }
  return points;
}

// How deep the surface of `a` reaches into the volume of `b` (0 when it does not).
inline double penetrationDepth(const PlacedMesh& a, const PlacedMesh& b, int steps = 8) {
  if (!a.box.intersects(b.box)) return 0.0;
  double deepest = 0.0;
  for (const auto& p : surfacePoints(a, steps)) {
    if (insideMesh(b, p)) deepest = std::max(deepest, distanceToSurface(b, p));
  }
  return deepest;
}

// Points on every triangle no farther than about `spacing` apart (a barycentric grid sized by the
// triangle's longest edge), vertices included: unlike surfacePoints, large faces get as dense a
// sampling as small ones.
inline std::vector<Eigen::Vector3d> surfaceSamples(const PlacedMesh& mesh, double spacing) {
  std::vector<Eigen::Vector3d> points = mesh.vertices;
  for (const auto& t : mesh.triangles) {
    const auto &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int steps = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= steps; ++i) {
      for (int j = 0; i + j <= steps; ++j) {
        points.push_back(a + (b - a) * (double(i) / steps) + (c - a) * (double(j) / steps));
      }
    }
  }
  return points;
}

// How deep the surface of `a` reaches into the volume of `b`, from samples `spacing` apart.
inline double sampledPenetrationDepth(const PlacedMesh& a, const PlacedMesh& b, double spacing) {
  if (!a.box.intersects(b.box)) return 0.0;
  double deepest = 0.0;
  for (const auto& p : surfaceSamples(a, spacing)) {
    if (insideMesh(b, p)) deepest = std::max(deepest, distanceToSurface(b, p));
  }
  return deepest;
}

inline double rotationAngleDeg(const Eigen::Matrix3d& r) {
  return Eigen::AngleAxisd(r).angle() * 180.0 / 3.14159265358979323846;
}

}  // namespace binpick::simulation::test
