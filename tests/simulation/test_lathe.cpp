#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

using test::closedManifoldProblem;
using test::signedVolume;

constexpr double kPi = 3.14159265358979323846;

// Area of the regular n-gon inscribed in a circle of radius r: the faceted cross-section.
double facetedDiscArea(double r, int n) { return 0.5 * n * r * r * std::sin(2.0 * kPi / n); }

double smallestTriangleArea(const io::TriangleMesh& mesh) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    smallest = std::min(smallest, 0.5 * (b - a).cross(c - a).norm());
  }
  return smallest;
}

// For a convex solid of revolution centred on the origin, every face normal points away from it.
void expectEveryFaceFacesAwayFromTheOrigin(const io::TriangleMesh& mesh) {
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0), 0.0);
  }
}

TEST(MakeLathe, CylinderIsClosedOutwardWithTheRevolvedVolume) {
  // r = 10 mm, h = 20 mm: the rectangle r in [0, 10], z in [-10, 10] mm, two points on the axis.
  constexpr int kSegments = 48;
  const io::TriangleMesh mesh = makeLathe({{0.0, -0.010}, {0.010, -0.010}, {0.010, 0.010}, {0.0, 0.010}}, kSegments);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_EQ(mesh.vertices.size(), 2u + 2u * kSegments);  // axis points collapse to one vertex
  EXPECT_EQ(mesh.triangles.size(), 4u * kSegments);      // two fans and one band of quads
  EXPECT_GT(smallestTriangleArea(mesh), 1e-9);
  expectEveryFaceFacesAwayFromTheOrigin(mesh);
  // Exactly the faceted prism's volume (up to float vertices) ...
  EXPECT_NEAR(signedVolume(mesh), facetedDiscArea(0.010, kSegments) * 0.020, 1e-12);
  // ... and the analytic pi r^2 h within the faceting error 1 - sin(t)/t ~ t^2/6 (t = 2 pi / n).
  const double analytic = kPi * 0.010 * 0.010 * 0.020;
  const double t = 2.0 * kPi / kSegments;
  EXPECT_NEAR(signedVolume(mesh), analytic, analytic * t * t / 6.0 * 1.01);
  EXPECT_LT(signedVolume(mesh), analytic);  // inscribed facets
}

TEST(MakeLathe, AnnulusWithoutAxisPointsHasTheRevolvedVolume) {
  constexpr int kSegments = 64;
  const io::TriangleMesh mesh =
      makeLathe({{0.012, -0.005}, {0.025, -0.005}, {0.025, 0.005}, {0.012, 0.005}}, kSegments);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_EQ(mesh.vertices.size(), 4u * kSegments);
  EXPECT_GT(smallestTriangleArea(mesh), 1e-9);
  const double faceted = (facetedDiscArea(0.025, kSegments) - facetedDiscArea(0.012, kSegments)) * 0.010;
  EXPECT_NEAR(signedVolume(mesh), faceted, 1e-12);
  const double analytic = kPi * (0.025 * 0.025 - 0.012 * 0.012) * 0.010;
  EXPECT_NEAR(signedVolume(mesh), analytic, 0.005 * analytic);
}

TEST(MakeLathe, DoubleConeWithSingleAxisPointsAndClockwiseProfile) {
  // A diamond touching the axis at its two tips, given clockwise: must be reversed.
  constexpr int kSegments = 32;
  const io::TriangleMesh mesh = makeLathe({{0.0, 1.0}, {1.0, 0.0}, {0.0, -1.0}}, kSegments);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_EQ(mesh.vertices.size(), 2u + kSegments);
  EXPECT_EQ(mesh.triangles.size(), 2u * kSegments);
  EXPECT_GT(smallestTriangleArea(mesh), 1e-6);
  expectEveryFaceFacesAwayFromTheOrigin(mesh);
  // Two cones of height 1 over the faceted unit disc.
  EXPECT_NEAR(signedVolume(mesh), 2.0 / 3.0 * facetedDiscArea(1.0, kSegments), 1e-6);
}

TEST(MakeLathe, FirstFacetIsOnPlusXAndRingsAreEvenlySpaced) {
  constexpr int kSegments = 8;
  const io::TriangleMesh mesh = makeLathe({{1.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}}, kSegments);
  std::set<long> angles;  // in units of 2 pi / segments
  for (const auto& v : mesh.vertices) {
    const double a = std::atan2(v.y(), v.x());
    const double steps = a / (2.0 * kPi / kSegments);
    EXPECT_NEAR(steps, std::round(steps), 1e-5);
    angles.insert((std::lround(steps) + kSegments) % kSegments);
  }
  EXPECT_EQ(angles.size(), static_cast<std::size_t>(kSegments));
  EXPECT_TRUE(angles.count(0));
}

TEST(MakeLathe, RejectsInvalidInput) {
  const std::vector<Eigen::Vector2d> square{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  EXPECT_THROW(makeLathe(square, 2), core::Error);
  EXPECT_NO_THROW(makeLathe(square, 3));
  EXPECT_THROW(makeLathe({{-0.5, 0}, {1, 0}, {1, 1}}, 16), core::Error);  // r < 0
  EXPECT_THROW(makeLathe({{0, 0}, {1, 0}}, 16), core::Error);
  EXPECT_THROW(makeLathe({{0, 0}, {1, 0}, {2, 0}}, 16), core::Error);          // zero area
  EXPECT_THROW(makeLathe({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 16), core::Error);  // self-intersecting
  try {
    makeLathe({{-0.5, 0}, {1, 0}, {1, 1}}, 16);
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("makeLathe"), std::string::npos);
  }
}

}  // namespace
}  // namespace binpick::simulation
