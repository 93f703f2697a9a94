#include "surface_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <unordered_map>
#include <utility>

#include "binpick/core/error.hpp"

namespace binpick::picking {
namespace {

// Neighbouring triangles (or cloud points) whose normals differ by less than this belong to one
// patch: a 64-facet cylinder's side is one face, a box's faces are six.
const double kPatchAngleCos = std::cos(15.0 * M_PI / 180.0);

Eigen::Vector3d toDouble(const Eigen::Vector3f& v) { return v.cast<double>(); }

// Keeps, in order, each point farther than `spacing` from every point kept before it.
std::vector<std::size_t> thinned(const std::vector<Eigen::Vector3d>& points, double spacing) {
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  const auto key = [&](const Eigen::Vector3i& c) {
    return (static_cast<std::int64_t>(c.x()) * 73856093) ^ (static_cast<std::int64_t>(c.y()) * 19349663) ^
           (static_cast<std::int64_t>(c.z()) * 83492791);
  };
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3i cell = (points[i] / spacing).array().floor().cast<int>();
    bool crowded = false;
    for (int dx = -1; dx <= 1 && !crowded; ++dx) {
      for (int dy = -1; dy <= 1 && !crowded; ++dy) {
        for (int dz = -1; dz <= 1 && !crowded; ++dz) {
          const auto found = grid.find(key(cell + Eigen::Vector3i(dx, dy, dz)));
          if (found == grid.end()) continue;
          for (std::size_t j : found->second) {
            if ((points[j] - points[i]).squaredNorm() < spacing * spacing) crowded = true;
          }
        }
      }
    }
    if (crowded) continue;
    grid[key(cell)].push_back(i);
    kept.push_back(i);
  }
  return kept;
}

// Patch ids by region growing over `neighbours` (adjacency lists) with similar normals.
std::vector<int> growPatches(const std::vector<Eigen::Vector3d>& normals,
                             const std::vector<std::vector<int>>& neighbours) {
  std::vector<int> patch(normals.size(), -1);
  int next = 0;
  for (std::size_t seed = 0; seed < normals.size(); ++seed) {
    if (patch[seed] >= 0) continue;
    std::vector<int> stack{static_cast<int>(seed)};
    patch[seed] = next;
    while (!stack.empty()) {
      const int current = stack.back();
      stack.pop_back();
      for (int other : neighbours[static_cast<std::size_t>(current)]) {
        if (patch[static_cast<std::size_t>(other)] >= 0) continue;
        if (normals[static_cast<std::size_t>(current)].dot(normals[static_cast<std::size_t>(other)]) < kPatchAngleCos) {
          continue;
        }
        patch[static_cast<std::size_t>(other)] = next;
        stack.push_back(other);
      }
    }
    ++next;
  }
  return patch;
}

// Triangles sharing an edge.
std::vector<std::vector<int>> edgeNeighbours(const std::vector<Eigen::Vector3i>& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int u = triangles[t][k], v = triangles[t][(k + 1) % 3];
      by_edge[{std::min(u, v), std::max(u, v)}].push_back(static_cast<int>(t));
    }
  }
  std::vector<std::vector<int>> neighbours(triangles.size());
  for (const auto& [edge, faces] : by_edge) {
    for (int f : faces) {
      for (int g : faces) {
        if (f != g) neighbours[static_cast<std::size_t>(f)].push_back(g);
      }
    }
  }
  return neighbours;
}

// The spacing that keeps the samples of `area` within `max_samples`.
double effectiveSpacing(double area, const GraspGenerationParams& params) {
  return std::max(params.sample_spacing, std::sqrt(area / params.max_samples));
}

}  // namespace

SurfaceModel SurfaceModel::fromMesh(const io::TriangleMesh& mesh, const GraspGenerationParams& params) {
  io::validateMesh(mesh, "grasp generation model");
  SurfaceModel surface;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> areas;
  Eigen::Vector3d volume_moment = Eigen::Vector3d::Zero(), area_moment = Eigen::Vector3d::Zero();
  double volume = 0.0, area = 0.0;
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    const Eigen::Vector3d a = toDouble(mesh.vertices[static_cast<std::size_t>(triangle[0])]);
    const Eigen::Vector3d b = toDouble(mesh.vertices[static_cast<std::size_t>(triangle[1])]);
    const Eigen::Vector3d c = toDouble(mesh.vertices[static_cast<std::size_t>(triangle[2])]);
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    if (!(cross.norm() > 1e-14)) continue;  // degenerate: no surface, no direction
    Primitive primitive{a, b, c, cross.normalized(), 0.0, 0};
    surface.primitives_.push_back(primitive);
    triangles.push_back(triangle);
    normals.push_back(primitive.normal);
    areas.push_back(0.5 * cross.norm());
    area += areas.back();
    area_moment += areas.back() * (a + b + c) / 3.0;
    const double signed_volume = a.dot(b.cross(c)) / 6.0;  // of the tetrahedron with the origin
    volume += signed_volume;
    volume_moment += signed_volume * (a + b + c) / 4.0;
  }
  if (!(area > 0.0)) throw core::Error("grasp generation model: the mesh has no area");
  // A closed mesh: its solid's centroid; an open one (no volume to speak of): its surface's.
  surface.centre_of_mass_ = std::abs(volume) > 1e-6 * area * std::sqrt(area) ? Eigen::Vector3d(volume_moment / volume)
                                                                             : Eigen::Vector3d(area_moment / area);
  const std::vector<int> patch = growPatches(normals, edgeNeighbours(triangles));
  for (std::size_t t = 0; t < surface.primitives_.size(); ++t) surface.primitives_[t].patch = patch[t];

  // Area-uniform random points, then thinned: an even spread whatever the triangulation.
  const double spacing = effectiveSpacing(area, params);
  const auto draws = static_cast<std::size_t>(std::ceil(8.0 * area / (spacing * spacing)));
  std::vector<double> cumulative(areas.size());
  std::partial_sum(areas.begin(), areas.end(), cumulative.begin());
  std::mt19937 random(params.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> owner;
  points.reserve(draws);
  for (std::size_t i = 0; i < draws; ++i) {
    const double pick = unit(random) * area;
    const auto t = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
                                 static_cast<std::ptrdiff_t>(areas.size()) - 1));
    const double r1 = std::sqrt(unit(random)), r2 = unit(random);
    const Primitive& tri = surface.primitives_[t];
    points.push_back((1.0 - r1) * tri.a + r1 * (1.0 - r2) * tri.b + r1 * r2 * tri.c);
    owner.push_back(t);
  }
  for (std::size_t i : thinned(points, spacing)) {
    const Primitive& tri = surface.primitives_[owner[i]];
    surface.samples_.push_back({points[i], tri.normal, tri.patch});
  }
  for (const SurfaceSample& sample : surface.samples_) surface.obstacles_.push_back(sample.point);
  for (const Eigen::Vector3f& vertex : mesh.vertices) surface.obstacles_.push_back(toDouble(vertex));
  surface.buildGrid();
  return surface;
}

SurfaceModel SurfaceModel::fromCloud(const io::PointCloud& cloud, const GraspGenerationParams& params) {
  io::validateCloud(cloud, "grasp generation model");
  if (!cloud.hasNormals()) throw core::Error("grasp generation model: the cloud has no normals");
  SurfaceModel surface;
  std::vector<Eigen::Vector3d> points, normals;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;  // an organized cloud's invalid pixel
    points.push_back(toDouble(cloud.points[i]));
    normals.push_back(toDouble(cloud.normals[i]).normalized());
  }
  if (points.size() < 3) throw core::Error("grasp generation model: the cloud has fewer than 3 valid points");
  // Every point becomes a disc; neighbour distances are first measured with discs of no size.
  for (std::size_t i = 0; i < points.size(); ++i) {
    surface.primitives_.push_back({points[i], points[i], points[i], normals[i], 0.0, 0});
  }
  Eigen::Vector3d low = points[0], high = points[0];
  for (const Eigen::Vector3d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  // Typical spacing of an even cloud covering the box's surface: a first guess for the grid.
  const Eigen::Vector3d extent = (high - low).cwiseMax(1e-6);
  const double box_area = 2.0 * (extent.x() * extent.y() + extent.y() * extent.z() + extent.z() * extent.x());
  surface.cell_size_ = std::max(std::sqrt(box_area / static_cast<double>(points.size())), 1e-5);
  surface.buildGrid();
  std::vector<double> nearest(points.size(), 0.0);
  std::vector<std::vector<int>> neighbours(points.size());
  std::vector<int> cells;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d reach = Eigen::Vector3d::Constant(2.0 * surface.cell_size_);
    surface.cellsOf(points[i] - reach, points[i] + reach, cells);
    double best = 4.0 * surface.cell_size_;
    for (int cell : cells) {
      for (int j : surface.cells_[static_cast<std::size_t>(cell)]) {
        if (static_cast<std::size_t>(j) != i)
          best = std::min(best, (points[static_cast<std::size_t>(j)] - points[i]).norm());
      }
    }
    nearest[i] = best;
  }
  std::vector<double> sorted = nearest;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double disc_radius = 1.5 * sorted[sorted.size() / 2];
  for (Primitive& primitive : surface.primitives_) primitive.disc_radius = disc_radius;
  surface.cell_size_ = 0.0;  // chosen afresh for the discs
  surface.buildGrid();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d reach = Eigen::Vector3d::Constant(2.0 * disc_radius);
    surface.cellsOf(points[i] - reach, points[i] + reach, cells);
    for (int cell : cells) {
      for (int j : surface.cells_[static_cast<std::size_t>(cell)]) {
        const auto other = static_cast<std::size_t>(j);
        if (other != i && (points[other] - points[i]).norm() <= 2.0 * disc_radius) neighbours[i].push_back(j);
      }
    }
  }
  const std::vector<int> patch = growPatches(normals, neighbours);
  for (std::size_t i = 0; i < points.size(); ++i) surface.primitives_[i].patch = patch[i];

  // Each point stands for about disc_radius^2 of surface (1.5 x its spacing, squared, / 2.25).
  const double area = static_cast<double>(points.size()) * disc_radius * disc_radius / 2.25;
  const double spacing = effectiveSpacing(area, params);
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(params.seed));
  std::vector<Eigen::Vector3d> shuffled;
  for (std::size_t i : order) shuffled.push_back(points[i]);
  for (std::size_t k : thinned(shuffled, spacing)) {
    const std::size_t i = order[k];
    surface.samples_.push_back({points[i], normals[i], patch[i]});
  }
  surface.obstacles_ = points;
  surface.centre_of_mass_ = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) surface.centre_of_mass_ += p;
  surface.centre_of_mass_ /= static_cast<double>(points.size());
  surface.buildGrid();  // also sets the radius
  return surface;
}

void SurfaceModel::buildGrid() {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = Eigen::Vector3d::Constant(-1e300);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes;
  for (const Primitive& p : primitives_) {
    Eigen::Vector3d box_low = p.a.cwiseMin(p.b).cwiseMin(p.c), box_high = p.a.cwiseMax(p.b).cwiseMax(p.c);
    box_low.array() -= p.disc_radius;
    box_high.array() += p.disc_radius;
    boxes.emplace_back(box_low, box_high);
    low = low.cwiseMin(box_low);
    high = high.cwiseMax(box_high);
  }
  const double extent = (high - low).maxCoeff();
  if (!(cell_size_ > 0.0)) cell_size_ = std::max({extent / 48.0, 4.0 * primitives_.front().disc_radius, 1e-5});
  cell_size_ = std::max(cell_size_, extent / 200.0);  // a bounded grid whatever the first guess
  grid_origin_ = low.array() - cell_size_;
  grid_dims_ = (((high - grid_origin_) / cell_size_).array().floor() + 2.0).cast<int>();
  cells_.assign(static_cast<std::size_t>(grid_dims_.prod()), {});
  std::vector<int> cells;
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    // Grown by half a cell: castRay's half-cell steps then meet every primitive the ray crosses.
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * cell_size_);
    cellsOf(boxes[i].first - half, boxes[i].second + half, cells);
    for (int cell : cells) cells_[static_cast<std::size_t>(cell)].push_back(static_cast<int>(i));
  }

  radius_ = 0.0;
  for (const Eigen::Vector3d& p : obstacles_) radius_ = std::max(radius_, (p - centre_of_mass_).norm());
}

int SurfaceModel::cellIndex(const Eigen::Vector3d& point) const {
  const Eigen::Vector3i c = ((point - grid_origin_) / cell_size_).array().floor().cast<int>();
  if ((c.array() < 0).any() || (c.array() >= grid_dims_.array()).any()) return -1;
  return (c.z() * grid_dims_.y() + c.y()) * grid_dims_.x() + c.x();
}

void SurfaceModel::cellsOf(const Eigen::Vector3d& low, const Eigen::Vector3d& high, std::vector<int>& cells) const {
  cells.clear();
  const Eigen::Vector3i from = ((low - grid_origin_) / cell_size_).array().floor().cast<int>().max(0);
  const Eigen::Vector3i to =
      ((high - grid_origin_) / cell_size_).array().floor().cast<int>().min(grid_dims_.array() - 1);
  for (int z = from.z(); z <= to.z(); ++z) {
    for (int y = from.y(); y <= to.y(); ++y) {
      for (int x = from.x(); x <= to.x(); ++x) cells.push_back((z * grid_dims_.y() + y) * grid_dims_.x() + x);
    }
  }
}

namespace {

// Möller-Trumbore, both faces; the distance along the ray, or nothing.
std::optional<double> hitTriangle(const SurfaceModel::Primitive& tri, const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& direction) {
  const Eigen::Vector3d e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-18) return std::nullopt;
  const Eigen::Vector3d s = origin - tri.a;
  const double u = s.dot(p) / det;
  if (u < -1e-9 || u > 1.0 + 1e-9) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = direction.dot(q) / det;
  if (v < -1e-9 || u + v > 1.0 + 1e-9) return std::nullopt;
  return e2.dot(q) / det;
}

std::optional<double> hitDisc(const SurfaceModel::Primitive& disc, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& direction) {
  const double facing = direction.dot(disc.normal);
  if (std::abs(facing) < 0.2) return std::nullopt;  // grazing: a disc seen edge-on is no surface
  const double distance = (disc.a - origin).dot(disc.normal) / facing;
  if ((origin + distance * direction - disc.a).norm() > disc.disc_radius) return std::nullopt;
  return distance;
}

}  // namespace

std::optional<RayHit> SurfaceModel::castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                            double max_distance, RayScratch& scratch) const {
  std::vector<std::uint32_t>& visit_stamp = scratch.visit_stamp_;
  // Entries added here hold 0, older ones earlier rays' stamps: all below this ray's.
  if (visit_stamp.size() < primitives_.size()) visit_stamp.resize(primitives_.size(), 0);
  if (++scratch.stamp_ == 0) {  // wrapped: forget every visit
    std::fill(visit_stamp.begin(), visit_stamp.end(), 0);
    scratch.stamp_ = 1;
  }
  const std::uint32_t stamp = scratch.stamp_;
  std::optional<RayHit> best;
  const double step = 0.5 * cell_size_;
  const int steps = static_cast<int>(std::ceil(max_distance / step));
  int last_cell = -2;
  for (int s = 0; s <= steps; ++s) {
    const double along = std::min(s * step, max_distance);
    if (best && along > best->distance + cell_size_) break;  // nothing nearer can come later
    const int cell = cellIndex(origin + along * direction);
    if (cell < 0 || cell == last_cell) continue;
    last_cell = cell;
    for (int index : cells_[static_cast<std::size_t>(cell)]) {
      if (visit_stamp[static_cast<std::size_t>(index)] == stamp) continue;
      visit_stamp[static_cast<std::size_t>(index)] = stamp;
      const Primitive& primitive = primitives_[static_cast<std::size_t>(index)];
      const std::optional<double> distance = primitive.disc_radius > 0.0 ? hitDisc(primitive, origin, direction)
                                                                         : hitTriangle(primitive, origin, direction);
      if (!distance || *distance < 0.0 || *distance > max_distance) continue;
      if (!best || *distance < best->distance) best = RayHit{*distance, primitive.normal, primitive.patch};
    }
  }
  return best;
}

}  // namespace binpick::picking
