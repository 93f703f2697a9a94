#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <set>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

using test::closedManifoldProblem;
using test::signedVolume;

std::vector<Eigen::Vector3d> verticesOf(const io::TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& v : mesh.vertices) out.push_back(v.cast<double>());
  return out;
}

// True when `rotation` maps the vertex set onto itself (every image lands on some vertex).
bool mapsVerticesOntoThemselves(const io::TriangleMesh& mesh, const Eigen::Matrix3d& rotation) {
  const auto vertices = verticesOf(mesh);
  for (const auto& v : vertices) {
    const Eigen::Vector3d image = rotation * v;
    const bool found = std::any_of(vertices.begin(), vertices.end(),
                                   [&](const Eigen::Vector3d& w) { return (w - image).norm() < 1e-6; });
    if (!found) return false;
  }
  return true;
}

// True when turning the part about `axis` by `angle` leaves it where it was, up to the faceting
// of a surface of revolution: every vertex and face centre of the turned mesh lies within
// `tolerance` of the original surface. A continuous axis is checked this way (a distance
// tolerance, not exact vertex matching), because the mesh is only n-fold symmetric: with n
// facets of radius r the turned surface strays at most the sagitta r (1 - cos(pi / n)) from the
// original, 0.03 mm for the 64-facet, 25 mm ring magnet, so a 0.1 mm tolerance accepts the
// faceting but rejects any real asymmetry (which moves points by millimetres).
bool turningAboutAxisKeepsTheSurface(const io::TriangleMesh& mesh, const Eigen::Vector3d& axis, double angle,
                                     double tolerance) {
  const test::PlacedMesh placed = test::place(mesh, Eigen::Isometry3d::Identity());
  std::vector<Eigen::Vector3d> points = placed.vertices;
  for (const auto& t : placed.triangles)
    points.push_back((placed.vertices[t[0]] + placed.vertices[t[1]] + placed.vertices[t[2]]) / 3.0);
  const Eigen::Matrix3d turn(Eigen::AngleAxisd(angle, axis.normalized()));
  return std::all_of(points.begin(), points.end(),
                     [&](const Eigen::Vector3d& p) { return test::distanceToSurface(placed, turn * p) < tolerance; });
}

constexpr double kContinuousAxisTolerance = 1e-4;  // 0.1 mm, see turningAboutAxisKeepsTheSurface
// Angles that are not multiples of 2 pi / n for any faceting n the parts use.
constexpr double kTestAngles[] = {0.1234, 1.0, 2.345, 4.0};

double twiceArea(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    sum += a.x() * b.y() - a.y() * b.x();
  }
  return sum;
}

TEST(Parts, NamesIncludeTheBuiltIns) {
  const auto names = partNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "l_bracket"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "clamp"), names.end());
  for (const char* name : {"gear", "l_bracket_long", "ring_magnet", "switch", "bulge"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  // No duplicates: every name selects one recipe.
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
}

TEST(Parts, UnknownNameThrowsNamingIt) {
  try {
    makePart("sprocket_xyz");
    FAIL() << "expected core::Error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("sprocket_xyz"), std::string::npos);
  }
}

TEST(Parts, EveryBuiltInIsClosedWithOutwardNormals) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const Part part = makePart(name);
    EXPECT_EQ(part.name, name);
    EXPECT_FALSE(part.description.empty());
    ASSERT_FALSE(part.mesh.empty());
    EXPECT_EQ(closedManifoldProblem(part.mesh), "");
    EXPECT_GT(signedVolume(part.mesh), 0.0);
  }
}

TEST(Parts, EveryBuiltInIsSizedLikeAnIndustrialPartInMetres) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const auto box = test::bounds(verticesOf(makePart(name).mesh));
    const double largest = box.sizes().maxCoeff();
    EXPECT_GE(largest, 0.040);
    EXPECT_LE(largest, 0.120);
  }
}

TEST(Parts, ModelOriginIsTheVolumeCentroid) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const io::TriangleMesh mesh = makePart(name).mesh;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double six_volume = 0.0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                            c = mesh.vertices[t[2]].cast<double>();
      const double v = a.dot(b.cross(c));
      six_volume += v;
      weighted += v * (a + b + c) / 4.0;
    }
    EXPECT_LT((weighted / six_volume).norm(), 1e-6);
  }
}

TEST(Parts, DeclaredSymmetriesMapThePartOntoItself) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const Part part = makePart(name);
    ASSERT_FALSE(part.symmetry.discrete.empty());
    EXPECT_TRUE(part.symmetry.discrete.front().isIdentity(1e-12));
    for (const auto& s : part.symmetry.discrete) {
      EXPECT_TRUE(s.isUnitary(1e-9));
      EXPECT_NEAR(s.determinant(), 1.0, 1e-9);  // proper rotations only
      EXPECT_TRUE(mapsVerticesOntoThemselves(part.mesh, s));
    }
    if (part.symmetry.continuous_axis) {
      const Eigen::Vector3d axis = *part.symmetry.continuous_axis;
      EXPECT_NEAR(axis.norm(), 1.0, 1e-12);
      for (const double angle : kTestAngles) {
        EXPECT_TRUE(turningAboutAxisKeepsTheSurface(part.mesh, axis, angle, kContinuousAxisTolerance))
            << "angle " << angle;
      }
      // The discrete rotations must map the axis onto itself (either way round).
      for (const auto& s : part.symmetry.discrete) EXPECT_NEAR(std::abs((s * axis).dot(axis)), 1.0, 1e-9);
    }
  }
}

// The declared discrete rotations form a group without repeats: products of symmetries are
// symmetries, so a list missing one (e.g. a flipped gear orientation) fails here.
TEST(Parts, DeclaredDiscreteSymmetriesFormAGroup) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const auto& group = makePart(name).symmetry.discrete;
    const auto contains = [&group](const Eigen::Matrix3d& r) {
      return std::count_if(group.begin(), group.end(),
                           [&r](const Eigen::Matrix3d& s) { return (s - r).norm() < 1e-9; });
    };
    for (const auto& a : group) {
      EXPECT_EQ(contains(a), 1);  // no repeats
      for (const auto& b : group) EXPECT_EQ(contains(a * b), 1);
    }
  }
}

// The checker above is not vacuous: a part without a continuous axis fails it.
TEST(Parts, ContinuousAxisCheckRejectsPartsWithoutOne) {
  for (const char* name : {"gear", "l_bracket", "bulge"}) {
    SCOPED_TRACE(name);
    const Part part = makePart(name);
    EXPECT_FALSE(
        turningAboutAxisKeepsTheSurface(part.mesh, Eigen::Vector3d::UnitZ(), 0.1234, kContinuousAxisTolerance));
  }
}

// The gear's 24 rotations are all of them: D12 is maximal among its finite symmetry groups about
// z (a 24-fold turn or a half-turn about an axis between a tooth and a gap would be next), and
// tilting the z axis is impossible for a thin disc.
TEST(Parts, GearHasExactlyTheDihedralSymmetryOfItsTwelveTeeth) {
  const Part gear = makePart("gear");
  EXPECT_EQ(gear.symmetry.discrete.size(), 24u);
  EXPECT_FALSE(gear.symmetry.continuous_axis);
  const double pitch = 2.0 * 3.14159265358979323846 / 12.0;
  const Eigen::Matrix3d half_pitch(Eigen::AngleAxisd(0.5 * pitch, Eigen::Vector3d::UnitZ()));
  EXPECT_FALSE(mapsVerticesOntoThemselves(gear.mesh, half_pitch));
  const Eigen::Vector3d between(std::cos(0.25 * pitch), std::sin(0.25 * pitch), 0.0);
  EXPECT_FALSE(
      mapsVerticesOntoThemselves(gear.mesh, Eigen::Matrix3d(Eigen::AngleAxisd(3.14159265358979323846, between))));
  // Every declared rotation keeps z an axis (turns fix it, flips reverse it), 12 of each.
  int flips = 0;
  for (const auto& s : gear.symmetry.discrete) flips += (s * Eigen::Vector3d::UnitZ()).z() < 0;
  EXPECT_EQ(flips, 12);
}

// The ring magnet: a continuous axis z and the flip; no further discrete rotations are needed
// because every half-turn about an in-plane axis is the flip composed with a turn about z.
TEST(Parts, RingMagnetIsTurnedWithAFlip) {
  const Part ring = makePart("ring_magnet");
  ASSERT_TRUE(ring.symmetry.continuous_axis);
  EXPECT_NEAR(ring.symmetry.continuous_axis->dot(Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
  ASSERT_EQ(ring.symmetry.discrete.size(), 2u);
  EXPECT_TRUE(ring.symmetry.discrete[1].isApprox(
      Eigen::Matrix3d(Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitX())), 1e-12));
  const auto box = test::bounds(verticesOf(ring.mesh));
  EXPECT_NEAR(box.sizes().x(), 0.050, 1e-6);
  EXPECT_NEAR(box.sizes().z(), 0.010, 1e-6);
  // The bore is open: no vertex within 12 mm of the axis.
  for (const auto& v : verticesOf(ring.mesh)) EXPECT_GT(v.head<2>().norm(), 0.012 - 1e-6);
}

// A proper symmetry preserves the second moment of the vertex set; with distinct eigenvalues it
// can only be a half-turn about a principal axis, so checking those three proves completeness.
TEST(Parts, PartsDeclaredAsymmetricHaveNoHiddenRotationalSymmetry) {
  for (const auto& name : partNames()) {
    const Part part = makePart(name);
    if (part.symmetry.discrete.size() != 1 || part.symmetry.continuous_axis) continue;
    SCOPED_TRACE(name);
    Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
    for (const auto& v : verticesOf(part.mesh)) moment += v * v.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(moment);
    const Eigen::Vector3d values = solver.eigenvalues();
    ASSERT_GT(values(1) - values(0), 0.01 * values(2));
    ASSERT_GT(values(2) - values(1), 0.01 * values(2));
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Matrix3d half_turn(Eigen::AngleAxisd(3.14159265358979323846, solver.eigenvectors().col(axis)));
      EXPECT_FALSE(mapsVerticesOntoThemselves(part.mesh, half_turn)) << "half-turn about principal axis " << axis;
    }
  }
}

TEST(MakePrism, ConcaveProfileGivesClosedMeshWithExactVolume) {
  // A comb: several reflex corners for the ear clipper.
  const std::vector<Eigen::Vector2d> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                          {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const io::TriangleMesh mesh = makePrism(comb, 0.5);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 0.5 * twiceArea(comb) / 2.0, 1e-9);
  EXPECT_EQ(mesh.vertices.size(), 2 * comb.size());
  EXPECT_EQ(mesh.triangles.size(), 2 * (comb.size() - 2) + 2 * comb.size());
}

TEST(MakePrism, CapsTileTheProfileWithoutOverlap) {
  const std::vector<Eigen::Vector2d> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                          {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const io::TriangleMesh mesh = makePrism(comb, 2.0);
  double top_area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    if (a.z() > 0 && b.z() > 0 && c.z() > 0) {
      const double z_normal = (b - a).cross(c - a).z();
      EXPECT_GT(z_normal, 0.0);  // every top triangle faces up: none is folded over
      top_area += 0.5 * z_normal;
    }
  }
  // Non-folded triangles whose areas add up to the profile's area cannot overlap or leave holes.
  EXPECT_NEAR(top_area, 0.5 * twiceArea(comb), 1e-5);
}

TEST(MakePrism, CapsSitAtPlusMinusHalfThickness) {
  const io::TriangleMesh mesh = makePrism({{0, 0}, {1, 0}, {0, 1}}, 0.2);
  for (const auto& v : mesh.vertices) EXPECT_NEAR(std::abs(v.z()), 0.1f, 1e-7f);
}

TEST(MakePrism, ClockwiseProfileStillGetsOutwardNormals) {
  const io::TriangleMesh mesh = makePrism({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, 1.0);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 1.0, 1e-9);
}

TEST(MakePrism, CollinearPointsAreDroppedAndTheMeshStaysClosed) {
  const io::TriangleMesh mesh = makePrism({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 1}}, 1.0);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 4.0, 1e-9);
}

TEST(MakePrism, RejectsSelfIntersectingProfile) {
  const std::vector<Eigen::Vector2d> bowtie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  EXPECT_THROW(makePrism(bowtie, 1.0), core::Error);
  // Edges that only touch at a point are also not a simple polygon.
  const std::vector<Eigen::Vector2d> touching{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}};
  EXPECT_THROW(makePrism(touching, 1.0), core::Error);
}

TEST(MakePrism, RejectsDegenerateInput) {
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}}, 1.0), core::Error);
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {2, 0}}, 1.0), core::Error);            // zero area
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0.5, 0}, {0, 1}}, 1.0), core::Error);  // doubles back
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0, 1}}, 0.0), core::Error);
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0, std::nan("")}}, 1.0), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
