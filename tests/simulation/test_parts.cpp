#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "binpick/io/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::sim {
namespace {

using test::closedManifoldProblem;
using test::signedVolume;

std::vector<Eigen::Vector3d> verticesOf(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& v : mesh.vertices) out.push_back(v.cast<double>());
  return out;
}

// True when `rotation` maps the vertex set onto itself (every image lands on some vertex).
bool mapsVerticesOntoThemselves(const TriangleMesh& mesh, const Eigen::Matrix3d& rotation) {
  const auto vertices = verticesOf(mesh);
  for (const auto& v : vertices) {
    const Eigen::Vector3d image = rotation * v;
    const bool found = std::any_of(vertices.begin(), vertices.end(), [&](const Eigen::Vector3d& w) {
      return (w - image).norm() < 1e-6;
    });
    if (!found) return false;
  }
  return true;
}

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
}

TEST(Parts, UnknownNameThrowsNamingIt) {
  try {
    makePart("sprocket_xyz");
    FAIL() << "expected binpick::Error";
  } catch (const Error& e) {
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
    const TriangleMesh mesh = makePart(name).mesh;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double six_volume = 0.0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(),
                            b = mesh.vertices[t[1]].cast<double>(),
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
    for (const auto& s : part.symmetry.discrete)
      EXPECT_TRUE(mapsVerticesOntoThemselves(part.mesh, s));
  }
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
      const Eigen::Matrix3d half_turn(
          Eigen::AngleAxisd(3.14159265358979323846, solver.eigenvectors().col(axis)));
      EXPECT_FALSE(mapsVerticesOntoThemselves(part.mesh, half_turn))
          << "half-turn about principal axis " << axis;
    }
  }
}

TEST(MakePrism, ConcaveProfileGivesClosedMeshWithExactVolume) {
  // A comb: several reflex corners for the ear clipper.
  const std::vector<Eigen::Vector2d> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                          {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const TriangleMesh mesh = makePrism(comb, 0.5);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 0.5 * twiceArea(comb) / 2.0, 1e-9);
  EXPECT_EQ(mesh.vertices.size(), 2 * comb.size());
  EXPECT_EQ(mesh.triangles.size(), 2 * (comb.size() - 2) + 2 * comb.size());
}

TEST(MakePrism, CapsTileTheProfileWithoutOverlap) {
  const std::vector<Eigen::Vector2d> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                          {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const TriangleMesh mesh = makePrism(comb, 2.0);
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
  const TriangleMesh mesh = makePrism({{0, 0}, {1, 0}, {0, 1}}, 0.2);
  for (const auto& v : mesh.vertices) EXPECT_NEAR(std::abs(v.z()), 0.1f, 1e-7f);
}

TEST(MakePrism, ClockwiseProfileStillGetsOutwardNormals) {
  const TriangleMesh mesh = makePrism({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, 1.0);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 1.0, 1e-9);
}

TEST(MakePrism, CollinearPointsAreDroppedAndTheMeshStaysClosed) {
  const TriangleMesh mesh = makePrism({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 1}}, 1.0);
  EXPECT_EQ(closedManifoldProblem(mesh), "");
  EXPECT_NEAR(signedVolume(mesh), 4.0, 1e-9);
}

TEST(MakePrism, RejectsSelfIntersectingProfile) {
  const std::vector<Eigen::Vector2d> bowtie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  EXPECT_THROW(makePrism(bowtie, 1.0), Error);
  // Edges that only touch at a point are also not a simple polygon.
  const std::vector<Eigen::Vector2d> touching{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}};
  EXPECT_THROW(makePrism(touching, 1.0), Error);
}

TEST(MakePrism, RejectsDegenerateInput) {
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}}, 1.0), Error);
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {2, 0}}, 1.0), Error);            // zero area
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0.5, 0}, {0, 1}}, 1.0), Error);  // doubles back
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0, 1}}, 0.0), Error);
  EXPECT_THROW(makePrism({{0, 0}, {1, 0}, {0, std::nan("")}}, 1.0), Error);
}

}  // namespace
}  // namespace binpick::sim
