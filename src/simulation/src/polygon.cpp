#include "polygon.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "binpick/core/error.hpp"

namespace binpick::simulation::detail {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Orientation of c relative to the directed line a->b: > 0 left, < 0 right, 0 on it.
double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

// Length scale used to turn "zero" into a tolerance that does not depend on the unit.
double polygonScale(const Polygon& polygon) {
  Eigen::Vector2d lo = polygon.front(), hi = polygon.front();
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return std::max((hi - lo).maxCoeff(), 1e-300);
}

bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

// Closed-segment intersection test, touching counts: a profile whose edges touch is not simple.
bool segmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d, double area_tolerance) {
  const double o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const double o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  const auto sign = [area_tolerance](double v) { return v > area_tolerance ? 1 : (v < -area_tolerance ? -1 : 0); };
  const int s1 = sign(o1), s2 = sign(o2), s3 = sign(o3), s4 = sign(o4);
  if (s1 * s2 < 0 && s3 * s4 < 0) return true;
  return (s1 == 0 && onSegment(a, b, c)) || (s2 == 0 && onSegment(a, b, d)) || (s3 == 0 && onSegment(c, d, a)) ||
         (s4 == 0 && onSegment(c, d, b));
}

Polygon withoutRepeatedAndCollinearVertices(const Polygon& profile, double length_tolerance) {
  Polygon polygon = profile;
  bool removed = true;
  // Repeat until stable: removing one vertex can make its neighbour collinear.
  while (removed && polygon.size() >= 3) {
    removed = false;
    const int n = static_cast<int>(polygon.size());
    for (int i = 0; i < n; ++i) {
      const auto& prev = polygon[(i + n - 1) % n];
      const auto& here = polygon[i];
      const auto& next = polygon[(i + 1) % n];
      const bool repeated = (here - prev).norm() <= length_tolerance;
      // Collinear and going forward (a spike that doubles back is a self-intersection instead).
      const bool straight = std::abs(orientation(prev, here, next)) <= length_tolerance * (next - prev).norm() &&
                            (here - prev).dot(next - here) > 0.0;
      if (repeated || straight) {
        polygon.erase(polygon.begin() + i);
        removed = true;
        break;
      }
    }
  }
  return polygon;
}

// `area_tolerance` is the orientation value (a cross product, length squared) treated as zero.
void requireNoCrossingEdges(const Polygon& polygon, double area_tolerance) {
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % n];
    for (int j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const auto& c = polygon[j];
      const auto& d = polygon[(j + 1) % n];
      if (adjacent) {
        // Neighbouring edges share a vertex; they overlap only if the polygon doubles back.
        const auto& shared = (j == i + 1) ? b : a;
        const auto& far_of_first = (j == i + 1) ? a : b;
        const auto& far_of_second = (j == i + 1) ? d : c;
        const bool collinear = std::abs(orientation(far_of_first, shared, far_of_second)) <= area_tolerance;
        const bool doubles_back = (far_of_first - shared).dot(far_of_second - shared) > 0.0;
        if (collinear && doubles_back) {
          throw core::Error("makePrism: the profile doubles back on itself at vertex " +
                            std::to_string((j == i + 1) ? j : i));
        }
        continue;
      }
      if (segmentsIntersect(a, b, c, d, area_tolerance)) {
        std::ostringstream message;
        message << "makePrism: the profile is self-intersecting (edge " << i << " crosses edge " << j << ")";
        throw core::Error(message.str());
      }
    }
  }
}

bool pointInTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c) {
  // Inclusive: a reflex vertex on the candidate ear's boundary must also block it.
  return orientation(a, b, p) >= 0.0 && orientation(b, c, p) >= 0.0 && orientation(c, a, p) >= 0.0;
}

bool isEar(const Polygon& polygon, const std::vector<int>& ring, std::size_t k) {
  const std::size_t n = ring.size();
  const int ia = ring[(k + n - 1) % n], ib = ring[k], ic = ring[(k + 1) % n];
  const auto &a = polygon[ia], &b = polygon[ib], &c = polygon[ic];
  if (orientation(a, b, c) <= 0.0) return false;  // reflex corner: the diagonal a-c is outside
  for (const int other : ring) {
    if (other == ia || other == ib || other == ic) continue;
    if (pointInTriangle(polygon[other], a, b, c)) return false;
  }
  return true;
}

}  // namespace

double twiceSignedArea(const Polygon& polygon) {
  double sum = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) sum += cross(polygon[i], polygon[(i + 1) % n]);
  return sum;
}

Polygon cleanSimplePolygon(const Polygon& profile) {
  if (profile.size() < 3) {
    throw core::Error("makePrism: the profile needs at least 3 points, got " + std::to_string(profile.size()));
  }
  for (const auto& p : profile) {
    if (!p.allFinite()) throw core::Error("makePrism: the profile has a non-finite coordinate");
  }
  const double scale = polygonScale(profile);
  const double length_tolerance = 1e-9 * scale;
  const double area_tolerance = 1e-9 * scale * scale;
  Polygon polygon = withoutRepeatedAndCollinearVertices(profile, length_tolerance);
  if (polygon.size() < 3 || std::abs(twiceSignedArea(polygon)) <= area_tolerance) {
    throw core::Error("makePrism: the profile has zero area");
  }
  requireNoCrossingEdges(polygon, area_tolerance);
  if (twiceSignedArea(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

std::vector<std::array<int, 3>> triangulateByEarClipping(const Polygon& polygon) {
  std::vector<int> ring(polygon.size());
  for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = static_cast<int>(i);
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(polygon.size() - 2);
  while (ring.size() > 3) {
    std::size_t ear = ring.size();
    for (std::size_t k = 0; k < ring.size(); ++k) {
      if (isEar(polygon, ring, k)) {
        ear = k;
        break;
      }
    }
    // A simple polygon always has an ear (two-ears theorem); only rounding can defeat that.
    if (ear == ring.size()) {
      throw core::Error("makePrism: could not triangulate the profile (nearly degenerate)");
    }
    const std::size_t n = ring.size();
    triangles.push_back({ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace binpick::simulation::detail
