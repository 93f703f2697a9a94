// Symmetry found from a mesh (mesh_symmetry.hpp).
#include "binpick/io/mesh_symmetry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "binpick/core/error.hpp"
#include "binpick/io/mesh_surface.hpp"

namespace binpick::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Triangle {
  Eigen::Vector3d a, b, c;
  double area() const { return 0.5 * (b - a).cross(c - a).norm(); }
};

Triangle triangleOf(const TriangleMesh& mesh, int index) {
  const Eigen::Vector3i& t = mesh.triangles[static_cast<std::size_t>(index)];
  return {mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(), mesh.vertices[t[2]].cast<double>()};
}

// The surface's centroid and the principal axes of its second moments about it, exact: over a
// triangle of area A, the integral of x x^T is A / 12 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
struct SurfaceMoments {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: unit principal axes
};

SurfaceMoments surfaceMoments(const TriangleMesh& mesh) {
  double area = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int i = 0; i < static_cast<int>(mesh.triangles.size()); ++i) {
    const Triangle t = triangleOf(mesh, i);
    const double a = t.area();
    const Eigen::Vector3d s = t.a + t.b + t.c;
    area += a;
    first += a * s / 3.0;
    second += a / 12.0 * (t.a * t.a.transpose() + t.b * t.b.transpose() + t.c * t.c.transpose() + s * s.transpose());
  }
  SurfaceMoments moments;
  if (!(area > 0.0)) return moments;
  moments.centroid = first / area;
  const Eigen::Matrix3d covariance = second / area - moments.centroid * moments.centroid.transpose();
  moments.axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  return moments;
}

// Points spread over the surface by area (seeded): the probes a rotation turns.
std::vector<Eigen::Vector3d> probePoints(const TriangleMesh& mesh, int count, uint64_t seed) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3f& p : sampleSurface(mesh, static_cast<std::size_t>(count), seed).points) {
    points.push_back(p.cast<double>());
  }
  return points;
}

// The closest point of a triangle to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Triangle& t) {
  const Eigen::Vector3d ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return t.a;
  const Eigen::Vector3d bp = p - t.b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return t.a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - t.c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return t.a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return t.b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (t.c - t.b);
  const double denominator = 1.0 / (va + vb + vc);
  return t.a + ab * (vb * denominator) + ac * (vc * denominator);
}

// The triangles bucketed by the cubic cells their bounding boxes touch: whether the surface
// passes within `reach` (at most a cell) of a point looks at the 27 cells around it.
class TriangleGrid {
 public:
  TriangleGrid(const TriangleMesh& mesh, double cell) : cell_(cell) {
    for (int i = 0; i < static_cast<int>(mesh.triangles.size()); ++i) {
      triangles_.push_back(triangleOf(mesh, i));
      const Triangle& t = triangles_.back();
      const Eigen::Vector3i low = cellOf(t.a.cwiseMin(t.b).cwiseMin(t.c));
      const Eigen::Vector3i high = cellOf(t.a.cwiseMax(t.b).cwiseMax(t.c));
      for (int x = low.x(); x <= high.x(); ++x)
        for (int y = low.y(); y <= high.y(); ++y)
          for (int z = low.z(); z <= high.z(); ++z) cells_[key({x, y, z})].push_back(i);
    }
  }

  bool near(const Eigen::Vector3d& p, double reach) const {
    const Eigen::Vector3i centre = cellOf(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find(key(centre + Eigen::Vector3i(dx, dy, dz)));
          if (found == cells_.end()) continue;
          for (const int i : found->second) {
            if ((closestOnTriangle(p, triangles_[static_cast<std::size_t>(i)]) - p).squaredNorm() <= reach * reach) {
              return true;
            }
          }
        }
    return false;
  }

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const { return (p / cell_).array().floor().cast<int>(); }
  static int64_t key(const Eigen::Vector3i& c) {
    return (static_cast<int64_t>(c.x()) * 73856093) ^ (static_cast<int64_t>(c.y()) * 19349663) ^
           (static_cast<int64_t>(c.z()) * 83492791);
  }
  double cell_;
  std::vector<Triangle> triangles_;
  std::unordered_map<int64_t, std::vector<int>> cells_;
};

// Whether a rotation about the origin maps every probe onto the surface.
struct SymmetryTest {
  const TriangleGrid& grid;
  const std::vector<Eigen::Vector3d>& probes;
  double reach;
  bool holds(const Eigen::Matrix3d& rotation) const {
    return std::all_of(probes.begin(), probes.end(),
                       [&](const Eigen::Vector3d& p) { return grid.near(rotation * p, reach); });
  }
};

Eigen::Matrix3d turn(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// Angles no small N divides, so that only a revolved part passes them all.
bool revolvedAbout(const Eigen::Vector3d& axis, const SymmetryTest& test) {
  for (const double degrees : {137.5, 11.3, 47.9, 83.1}) {
    if (!test.holds(turn(axis, degrees * kPi / 180.0))) return false;
  }
  return true;
}

// Whether every turn by a multiple of 2 pi / n maps the part onto itself. The first decides
// most n; the others catch a small turn that passes only for being small (an octagonal collar
// turned by 6 degrees strays 0.35 mm from itself, by 24 degrees 0.7 mm).
bool nFold(const Eigen::Vector3d& axis, int n, const SymmetryTest& test) {
  for (int k = 1; k < n; ++k) {
    if (!test.holds(turn(axis, 2.0 * kPi * k / n))) return false;
  }
  return true;
}

// The largest N <= max_order whose turns map the part onto itself; 1 for none.
int turnsAbout(const Eigen::Vector3d& axis, const SymmetryTest& test, int max_order) {
  for (int n = max_order; n >= 2; --n) {
    if (nFold(axis, n, test)) return n;
  }
  return 1;
}

// A perpendicular axis whose half-turn maps the part onto itself: the principal axes first, then
// directions around `axis` a degree apart over the half-period pi / turns (N-fold: the 2-fold
// axes repeat every pi / N).
std::optional<Eigen::Vector3d> flipAxis(const Eigen::Vector3d& axis, int turns, const Eigen::Matrix3d& principal,
                                        const SymmetryTest& test) {
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d candidate = principal.col(k);
    if (std::abs(candidate.dot(axis)) < 1e-6 && test.holds(turn(candidate, kPi))) return candidate;
  }
  if (turns == 0) return std::nullopt;  // revolved: one perpendicular axis speaks for all
  const Eigen::Vector3d u = axis.unitOrthogonal();
  const Eigen::Vector3d v = axis.cross(u);
  const double span = kPi / turns;
  const int steps = static_cast<int>(std::ceil(span / (kPi / 180.0)));
  for (int s = 0; s < steps; ++s) {
    const double angle = span * s / steps;
    const Eigen::Vector3d candidate = std::cos(angle) * u + std::sin(angle) * v;
    if (test.holds(turn(candidate, kPi))) return candidate;
  }
  return std::nullopt;
}

// The axis with its largest component positive: the same text for a part however it was found.
Eigen::Vector3d canonical(Eigen::Vector3d axis) {
  Eigen::Index largest = 0;
  axis.cwiseAbs().maxCoeff(&largest);
  return axis[largest] < 0.0 ? Eigen::Vector3d(-axis) : axis;
}

std::string vectorText(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.3g, %.3g, %.3g)", std::abs(v.x()) < 5e-4 ? 0.0 : v.x(),
                std::abs(v.y()) < 5e-4 ? 0.0 : v.y(), std::abs(v.z()) < 5e-4 ? 0.0 : v.z());
  return text;
}

Symmetry groupOf(const Eigen::Vector3d& axis, int turns, const std::optional<Eigen::Vector3d>& flip) {
  Symmetry symmetry;
  if (turns == 0) symmetry.continuous_axis = axis;
  for (int k = 1; k < std::max(turns, 1); ++k) symmetry.discrete.push_back(turn(axis, 2.0 * kPi * k / turns));
  if (!flip) return symmetry;
  const Eigen::Matrix3d half = turn(*flip, kPi);
  const std::size_t count = symmetry.discrete.size();
  for (std::size_t k = 0; k < count; ++k) symmetry.discrete.push_back(symmetry.discrete[k] * half);
  return symmetry;
}

}  // namespace

void SymmetryParams::validate() const {
  const std::string owner = "SymmetryParams";
  core::requireField(std::isfinite(tolerance) && tolerance > 0.0 && tolerance < 0.5, owner, "tolerance", "in (0, 0.5)",
                     tolerance);
  core::requireField(max_order >= 2 && max_order <= 360, owner, "max_order", "in [2, 360]", max_order);
  core::requireField(probes >= 10 && probes <= 1000000, owner, "probes", "in [10, 1000000]", probes);
}

FoundSymmetry findSymmetry(const TriangleMesh& mesh, const SymmetryParams& params) {
  params.validate();
  validateMesh(mesh, "findSymmetry");
  if (mesh.empty()) throw core::Error("findSymmetry: the mesh has no triangles");
  Eigen::Vector3f low = mesh.vertices.front(), high = low;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  const double reach = params.tolerance * (high - low).cast<double>().norm();
  FoundSymmetry found;
  found.description = "none";
  if (!(reach > 0.0)) return found;
  const SurfaceMoments moments = surfaceMoments(mesh);
  const TriangleGrid grid(mesh, reach);
  const std::vector<Eigen::Vector3d> probes = probePoints(mesh, params.probes, params.seed);
  const SymmetryTest test{grid, probes, reach};
  const bool centred = moments.centroid.norm() <= reach;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = canonical(moments.axes.col(k));
    // A turn about the origin keeps the centroid only when the axis passes through both.
    if ((moments.centroid - moments.centroid.dot(axis) * axis).norm() > reach) continue;
    const int turns = revolvedAbout(axis, test) ? 0 : turnsAbout(axis, test, params.max_order);
    const bool better = turns == 0 ? found.turns != 0 : (found.turns != 0 && turns > found.turns);
    if (!better) continue;
    found.axis = axis;
    found.turns = turns;
  }
  if (found.turns == 1) {
    if (!centred)
      found.description =
          "none about the model origin (the surface's centroid lies " + vectorText(moments.centroid) + " from it)";
    return found;
  }
  const std::optional<Eigen::Vector3d> flip =
      centred ? flipAxis(found.axis, found.turns, moments.axes, test) : std::nullopt;
  found.flips = flip.has_value();
  found.symmetry = groupOf(found.axis, found.turns, flip);
  found.description = (found.turns == 0 ? "revolved" : std::to_string(found.turns) + "-fold") + " about " +
                      vectorText(found.axis) + (found.flips ? ", flips over" : "") + ": " +
                      describeSymmetry(found.symmetry);
  return found;
}

std::string describeSymmetry(const Symmetry& symmetry) {
  const std::size_t count = symmetry.discrete.size();
  if (!symmetry.continuous_axis && count <= 1) return "none";
  const std::string rotations = std::to_string(count) + (count == 1 ? " rotation" : " rotations");
  if (!symmetry.continuous_axis) return rotations;
  const std::string turns = "any turn about " + vectorText(*symmetry.continuous_axis);
  return count <= 1 ? turns : turns + " with " + rotations;
}

}  // namespace binpick::io
