// Symmetry found from a mesh (binpick/io/mesh_symmetry.hpp): on primitives, on faceted CAD-like
// solids and on every built-in part, whose symmetry is declared by hand.
#include "binpick/io/mesh_symmetry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"

namespace binpick::simulation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Whether `rotation` is one of `group`'s (to 1e-6).
bool holds(const std::vector<Eigen::Matrix3d>& group, const Eigen::Matrix3d& rotation) {
  for (const Eigen::Matrix3d& r : group) {
    if ((r - rotation).norm() < 1e-6) return true;
  }
  return false;
}

// The same group: the same rotations and a parallel continuous axis.
void expectSameSymmetry(const io::Symmetry& found, const Symmetry& declared, const std::string& name) {
  EXPECT_EQ(found.discrete.size(), declared.discrete.size()) << name;
  EXPECT_TRUE(found.discrete.front().isIdentity(1e-12)) << name;
  for (const Eigen::Matrix3d& r : declared.discrete) EXPECT_TRUE(holds(found.discrete, r)) << name << "\n" << r;
  ASSERT_EQ(found.continuous_axis.has_value(), declared.continuous_axis.has_value()) << name;
  if (found.continuous_axis) {
    EXPECT_GT(std::abs(found.continuous_axis->dot(*declared.continuous_axis)), 1.0 - 1e-9) << name;
  }
}

io::TriangleMesh box(double x, double y, double z) {
  const std::vector<Eigen::Vector2d> profile{{-x / 2, -y / 2}, {x / 2, -y / 2}, {x / 2, y / 2}, {-x / 2, y / 2}};
  return makePrism(profile, z);
}

io::TriangleMesh regularPrism(int sides, double radius, double thickness) {
  std::vector<Eigen::Vector2d> profile;
  for (int k = 0; k < sides; ++k) {
    profile.emplace_back(radius * std::cos(2 * kPi * k / sides), radius * std::sin(2 * kPi * k / sides));
  }
  return makePrism(profile, thickness);
}

// A stepped shaft: 10 mm thick, 80 mm long, a 20 mm collar 10 mm long at one end; in metres.
io::TriangleMesh steppedShaft(int segments) {
  return makeLathe({{0, -0.040}, {0.005, -0.040}, {0.005, 0.030}, {0.010, 0.030}, {0.010, 0.040}, {0, 0.040}},
                   segments);
}

TEST(MeshSymmetry, EveryBuiltInPartHasTheSymmetryItDeclares) {
  for (const std::string& name : partNames()) {
    const Part part = makePart(name);
    const io::FoundSymmetry found = io::findSymmetry(part.mesh);
    SCOPED_TRACE(name + ": " + found.description);
    expectSameSymmetry(found.symmetry, part.symmetry, name);
  }
}

TEST(MeshSymmetry, TheGearTurnsTwelveWaysAndFlipsOver) {
  const io::FoundSymmetry found = io::findSymmetry(makePart("gear").mesh);
  EXPECT_EQ(found.turns, 12);
  EXPECT_TRUE(found.flips);
  EXPECT_GT(std::abs(found.axis.z()), 1.0 - 1e-9);
  EXPECT_EQ(found.description, "12-fold about (0, 0, 1), flips over: 24 rotations");
}

TEST(MeshSymmetry, BoxesAndRegularPrismsTurnAndFlip) {
  const io::FoundSymmetry brick = io::findSymmetry(box(0.08, 0.05, 0.02));
  EXPECT_EQ(brick.turns, 2);
  EXPECT_TRUE(brick.flips);
  EXPECT_EQ(brick.symmetry.discrete.size(), 4u);  // the identity and a half-turn about each axis
  const io::FoundSymmetry hexagon = io::findSymmetry(regularPrism(6, 0.02, 0.01));
  EXPECT_EQ(hexagon.turns, 6);
  EXPECT_TRUE(hexagon.flips);
  EXPECT_EQ(hexagon.symmetry.discrete.size(), 12u);
  EXPECT_TRUE(
      holds(hexagon.symmetry.discrete, Eigen::AngleAxisd(kPi / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
}

// CAD exports a cylinder as facets: with 24 or more about a 10 mm shaft the facets stray from
// the circle by less than the tolerance (0.5% of the part's size), and it counts as revolved;
// 8 facets are a prism of 8 sides.
TEST(MeshSymmetry, AFacetedShaftIsRevolvedAndItsCollarKeepsItFromFlipping) {
  for (const int segments : {24, 64}) {
    const io::FoundSymmetry shaft = io::findSymmetry(steppedShaft(segments));
    EXPECT_EQ(shaft.turns, 0) << segments << " segments: " << shaft.description;
    ASSERT_TRUE(shaft.symmetry.continuous_axis.has_value());
    EXPECT_GT(std::abs(shaft.symmetry.continuous_axis->z()), 1.0 - 1e-9);
    EXPECT_FALSE(shaft.flips) << "the collar is at one end";
  }
  const io::FoundSymmetry octagon = io::findSymmetry(steppedShaft(8));
  EXPECT_EQ(octagon.turns, 8) << octagon.description;
}

// A model origin on the axis but off the centroid (CAD often puts it at one end) keeps the turns
// and loses the flips; an origin off the axis keeps nothing, and says why.
TEST(MeshSymmetry, TheModelOriginDecidesWhatCanBeKept) {
  io::TriangleMesh end_origin = steppedShaft(64);
  for (Eigen::Vector3f& v : end_origin.vertices) v.z() += 0.040f;
  const io::FoundSymmetry at_end = io::findSymmetry(end_origin);
  EXPECT_EQ(at_end.turns, 0) << at_end.description;

  io::TriangleMesh aside = box(0.08, 0.05, 0.02);
  for (Eigen::Vector3f& v : aside.vertices) v.x() += 0.030f;
  const io::FoundSymmetry off_axis = io::findSymmetry(aside);
  EXPECT_EQ(off_axis.turns, 2) << "the half-turn about the x axis still holds: " << off_axis.description;
  EXPECT_FALSE(off_axis.flips);

  io::TriangleMesh shifted = regularPrism(6, 0.02, 0.01);
  for (Eigen::Vector3f& v : shifted.vertices) v += Eigen::Vector3f(0.03f, 0.02f, 0.0f);
  const io::FoundSymmetry none = io::findSymmetry(shifted);
  EXPECT_EQ(none.turns, 1);
  EXPECT_EQ(none.symmetry.discrete.size(), 1u);
  EXPECT_NE(none.description.find("none about the model origin"), std::string::npos) << none.description;
}

TEST(MeshSymmetry, BadInputIsNamed) {
  EXPECT_THROW(io::findSymmetry(io::TriangleMesh{}), core::Error);
  io::SymmetryParams params;
  params.tolerance = 0.0;
  EXPECT_THROW(io::findSymmetry(box(0.01, 0.01, 0.01), params), core::Error);
  io::TriangleMesh broken = box(0.01, 0.01, 0.01);
  broken.vertices[0].x() = std::nanf("");
  EXPECT_THROW(io::findSymmetry(broken), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
