#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

// What a settled pile must satisfy, measured on the real meshes (not on Bullet's shapes).
constexpr double kInsideTolerance = 1e-3;  // metres beyond the inner walls or below the floor
constexpr double kSupportGap = 3e-3;       // metres between a part and what holds it up
constexpr double kMaxPenetration = 2e-3;   // metres of one part's surface inside another
constexpr double kSampleSpacing = 1e-3;    // metres between surface samples of the checks

// A closed torus (radii 22 and 7 mm, 32 x 16 facets) tilted, with its model origin 15 mm off its
// centroid: a mesh as a user loads it from a file, following none of the built-in parts'
// conventions.
io::TriangleMesh userTorus() {
  constexpr int kAround = 32, kSection = 16;
  constexpr double kPi = 3.14159265358979323846, kRing = 0.022, kTube = 0.007;
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d origin_offset(0.015, -0.004, 0.002);
  io::TriangleMesh mesh;
  for (int i = 0; i < kAround; ++i) {
    for (int j = 0; j < kSection; ++j) {
      const double u = 2.0 * kPi * i / kAround, v = 2.0 * kPi * j / kSection;
      const double r = kRing + kTube * std::cos(v);
      const Eigen::Vector3d p(r * std::cos(u), r * std::sin(u), kTube * std::sin(v));
      mesh.vertices.push_back((tilt * p + origin_offset).cast<float>());
    }
  }
  const auto id = [&](int i, int j) { return (i % kAround) * kSection + j % kSection; };
  for (int i = 0; i < kAround; ++i) {
    for (int j = 0; j < kSection; ++j) {
      mesh.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mesh.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return mesh;
}

std::vector<test::PlacedMesh> placeAll(const io::TriangleMesh& part, const PhysicsPile& pile) {
  std::vector<test::PlacedMesh> placed;
  for (const auto& T_bin_object : pile.T_bin_object) placed.push_back(test::place(part, T_bin_object));
  return placed;
}

bool insideBin(const test::PlacedMesh& part, const BinInterior& bin) {
  const double x = 0.5 * bin.length + kInsideTolerance, y = 0.5 * bin.width + kInsideTolerance;
  return part.box.min().x() >= -x && part.box.max().x() <= x && part.box.min().y() >= -y && part.box.max().y() <= y &&
         part.box.min().z() >= -kInsideTolerance;
}

Eigen::AlignedBox3d grown(Eigen::AlignedBox3d box, double by) {
  box.min().array() -= by;
  box.max().array() += by;
  return box;
}

// Resting under gravity, a part touches the floor or another part: none hovers.
bool supported(const std::vector<test::PlacedMesh>& placed, std::size_t i) {
  if (placed[i].box.min().z() <= kSupportGap) return true;
  const std::vector<Eigen::Vector3d> samples = test::surfaceSamples(placed[i], kSampleSpacing);
  for (std::size_t j = 0; j < placed.size(); ++j) {
    if (j == i) continue;
    const Eigen::AlignedBox3d near = grown(placed[j].box, kSupportGap);
    for (const auto& p : samples) {
      if (near.contains(p) && test::distanceToSurface(placed[j], p) <= kSupportGap) return true;
    }
  }
  return false;
}

// Checks every pair of parts that come close; returns how many such pairs there are.
int expectNoInterpenetration(const std::vector<test::PlacedMesh>& placed) {
  int close_pairs = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    for (std::size_t j = 0; j < placed.size(); ++j) {
      if (i == j || !placed[i].box.intersects(placed[j].box)) continue;
      ++close_pairs;
      EXPECT_LT(test::sampledPenetrationDepth(placed[i], placed[j], kSampleSpacing), kMaxPenetration)
          << "part " << i << " into part " << j;
    }
  }
  return close_pairs;
}

// A small bin makes a pile several parts deep, with many contacts.
void expectSettledPhysicalPile(const io::TriangleMesh& part, int objects) {
  const BinInterior bin{0.20, 0.16, 0.15};
  const PhysicsParams params;
  const PhysicsPile pile = simulatePile(part, objects, bin, params, 3);
  EXPECT_TRUE(pile.settled);
  EXPECT_EQ(pile.lost, 0);
  ASSERT_EQ(pile.T_bin_object.size(), static_cast<std::size_t>(objects));
  EXPECT_GT(pile.simulated_time, 0.0);
  EXPECT_LE(pile.simulated_time, params.max_simulated_time);
  EXPECT_EQ(pile.steps, std::lround(pile.simulated_time / params.time_step) * static_cast<long>(params.substeps));
  EXPECT_GE(pile.layers, 1);
  const std::vector<test::PlacedMesh> placed = placeAll(part, pile);
  for (std::size_t i = 0; i < placed.size(); ++i) {
    EXPECT_TRUE(insideBin(placed[i], bin)) << "part " << i;
    EXPECT_TRUE(supported(placed, i)) << "part " << i << " hovers";
  }
  EXPECT_GT(expectNoInterpenetration(placed), 3);  // the check only means something with contacts
}

TEST(PhysicsPile, SameSeedGivesBitIdenticalPosesAndOtherSeedsDiffer) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  const BinInterior bin;
  const PhysicsParams params;
  const PhysicsPile first = simulatePile(part, 8, bin, params, 5);
  const PhysicsPile again = simulatePile(part, 8, bin, params, 5);
  ASSERT_EQ(first.T_bin_object.size(), again.T_bin_object.size());
  for (std::size_t i = 0; i < first.T_bin_object.size(); ++i) {
    EXPECT_TRUE(first.T_bin_object[i].matrix() == again.T_bin_object[i].matrix()) << "part " << i;
  }
  EXPECT_EQ(first.steps, again.steps);
  const PhysicsPile other = simulatePile(part, 8, bin, params, 6);
  EXPECT_FALSE(first.T_bin_object[0].isApprox(other.T_bin_object[0], 1e-6));
}

TEST(PhysicsPile, LBracketsSettleInsideSupportedAndApart) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  expectSettledPhysicalPile(part, 12);
  // Two legs need two convex pieces: one hull would fill the corner.
  EXPECT_GE(simulatePile(part, 1, BinInterior{}, PhysicsParams{}, 1).convex_pieces, 2);
}

TEST(PhysicsPile, RingMagnetsSettleInsideSupportedAndApart) {
  expectSettledPhysicalPile(makePart("ring_magnet").mesh, 12);
}

TEST(PhysicsPile, UserMeshSettlesInsideSupportedAndApart) { expectSettledPhysicalPile(userTorus(), 10); }

// A part resting on its own inside the ring's hole proves that the hole is not filled in.
TEST(PhysicsPile, RingMagnetPiecesLeaveTheHoleOpen) {
  const io::TriangleMesh ring = makePart("ring_magnet").mesh;
  EXPECT_GE(simulatePile(ring, 1, BinInterior{}, PhysicsParams{}, 1).convex_pieces, 4);
}

// Low walls and a small floor: parts spill over. Whatever went over is dropped again or reported
// lost, and what comes back lies inside.
TEST(PhysicsPile, PartsOutsideTheBinAreNeverReturned) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  const BinInterior bin{0.13, 0.13, 0.004};
  PhysicsParams params;
  params.max_simulated_time = 4.0;
  const PhysicsPile pile = simulatePile(part, 10, bin, params, 2);
  EXPECT_GT(pile.redrops + pile.lost, 0);  // the scenario did make parts spill
  EXPECT_EQ(static_cast<int>(pile.T_bin_object.size()) + pile.lost, 10);
  for (const auto& placed : placeAll(part, pile)) EXPECT_TRUE(insideBin(placed, bin));
}

// The checks themselves must be able to fail.
TEST(PhysicsPile, ChecksDetectOverlapHoveringAndEscape) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  Eigen::Isometry3d resting = Eigen::Isometry3d::Identity();
  resting.translation() = Eigen::Vector3d(0.0, 0.0, 0.016);  // 30 mm wide along z: on the floor
  Eigen::Isometry3d overlapping = resting;
  overlapping.translation() += Eigen::Vector3d(0.004, 0.003, 0.005);
  EXPECT_GT(test::sampledPenetrationDepth(test::place(part, resting), test::place(part, overlapping), kSampleSpacing),
            kMaxPenetration);
  Eigen::Isometry3d hovering = resting;
  hovering.translation() += Eigen::Vector3d(0.0, 0.0, 0.01);
  EXPECT_FALSE(supported({test::place(part, hovering)}, 0));
  EXPECT_TRUE(supported({test::place(part, resting)}, 0));
  Eigen::Isometry3d over_the_wall = resting;
  over_the_wall.translation().x() = 0.19;
  EXPECT_FALSE(insideBin(test::place(part, over_the_wall), BinInterior{}));
}

TEST(PhysicsPile, EmptyPileIsAValue) {
  const PhysicsPile pile = simulatePile(makePart("clamp").mesh, 0, BinInterior{}, PhysicsParams{}, 1);
  EXPECT_TRUE(pile.settled);
  EXPECT_TRUE(pile.T_bin_object.empty());
  EXPECT_EQ(pile.steps, 0);
}

TEST(PhysicsPile, RejectsBadInput) {
  const io::TriangleMesh part = makePart("clamp").mesh;
  io::TriangleMesh inside_out = part;
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_THROW(simulatePile(inside_out, 1, BinInterior{}, PhysicsParams{}, 1), core::Error);
  EXPECT_THROW(simulatePile(io::TriangleMesh{}, 1, BinInterior{}, PhysicsParams{}, 1), core::Error);
  EXPECT_THROW(simulatePile(part, -1, BinInterior{}, PhysicsParams{}, 1), core::Error);
  EXPECT_THROW(simulatePile(part, 1, BinInterior{0.4, -0.3, 0.15}, PhysicsParams{}, 1), core::Error);
  EXPECT_THROW(simulatePile(part, 1, BinInterior{0.05, 0.05, 0.15}, PhysicsParams{}, 1), core::Error);
}

std::string validationMessage(const PhysicsParams& params, const std::string& name) {
  try {
    params.validate(name);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(PhysicsParams, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(PhysicsParams{}.validate());
  const auto message = [](void (*change)(PhysicsParams&)) {
    PhysicsParams params;
    change(params);
    return validationMessage(params, "PhysicsParams");
  };
  EXPECT_NE(message([](PhysicsParams& p) { p.friction = -0.1; }).find("PhysicsParams.friction"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.restitution = 1.5; }).find("restitution"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.drop_height_max = 0.01; }).find("drop_height_max"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.time_step = 0.0; }).find("time_step"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.substeps = 0; }).find("substeps"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.settle_angular_velocity = std::nan(""); }).find("settle_angular_velocity"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.decomposition_tolerance = 0.0; }).find("decomposition_tolerance"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.max_convex_pieces = 0; }).find("max_convex_pieces"), std::string::npos);
  EXPECT_NE(message([](PhysicsParams& p) { p.collision_margin = -1.0; }).find("collision_margin"), std::string::npos);
  // simulatePile validates too, under the name of the struct.
  PhysicsParams bad;
  bad.max_simulated_time = -1.0;
  try {
    simulatePile(makePart("clamp").mesh, 1, BinInterior{}, bad, 1);
    ADD_FAILURE() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("PhysicsParams.max_simulated_time"), std::string::npos);
  }
}

}  // namespace
}  // namespace binpick::simulation
