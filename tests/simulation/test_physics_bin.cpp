#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "binpick/simulation/pile.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

// A flat box, 40 x 30 x 12 mm: in a bin hardly larger than it, five of them stack.
io::TriangleMesh flatBox() {
  return makePrism({{-0.020, -0.015}, {0.020, -0.015}, {0.020, 0.015}, {-0.020, 0.015}}, 0.012);
}

// Hardly wider than the box's diagonal: the boxes stack on each other, some on edge.
const BinInterior kNarrowBin{0.055, 0.055, 0.15};

double lowestZ(const io::TriangleMesh& part, const Eigen::Isometry3d& T_bin_object) {
  return test::place(part, T_bin_object).box.min().z();
}

// The part highest in the pile, and the part that holds it up: the one its surface comes closest to.
std::pair<int, int> topAndSupport(const io::TriangleMesh& part, const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<test::PlacedMesh> placed;
  for (const auto& pose : poses) placed.push_back(test::place(part, pose));
  int top = 0;
  for (std::size_t i = 1; i < placed.size(); ++i) {
    if (placed[i].box.min().z() > placed[top].box.min().z()) top = static_cast<int>(i);
  }
  const std::vector<Eigen::Vector3d> samples = test::surfaceSamples(placed[top], 0.002);
  int support = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < placed.size(); ++j) {
    if (static_cast<int>(j) == top) continue;
    for (const auto& p : samples) {
      const double distance = test::distanceToSurface(placed[j], p);
      if (distance < nearest) {
        nearest = distance;
        support = static_cast<int>(j);
      }
    }
  }
  return {top, support};
}

TEST(PhysicsBin, FirstDropIsSimulatePileBitForBit) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  const BinInterior bin{0.20, 0.16, 0.15};
  const PhysicsParams params;
  const PhysicsPile expected = simulatePile(part, 6, bin, params, 4);
  PhysicsBin physics_bin(part, bin, params, 4);
  const PhysicsPile dropped = physics_bin.drop(6);
  ASSERT_EQ(dropped.T_bin_object.size(), expected.T_bin_object.size());
  for (std::size_t i = 0; i < expected.T_bin_object.size(); ++i) {
    EXPECT_TRUE(dropped.T_bin_object[i].matrix() == expected.T_bin_object[i].matrix()) << i;
  }
  EXPECT_EQ(dropped.steps, expected.steps);
  EXPECT_EQ(dropped.layers, expected.layers);
  const std::vector<Eigen::Isometry3d> poses = physics_bin.poses();
  ASSERT_EQ(poses.size(), expected.T_bin_object.size());
  EXPECT_TRUE(poses.back().matrix() == expected.T_bin_object.back().matrix());
}

// Taking out the part that holds another up lets that one fall into a new place.
TEST(PhysicsBin, PartAboveMovesDownWhenItsSupportIsRemoved) {
  const io::TriangleMesh part = flatBox();
  PhysicsBin bin(part, kNarrowBin, PhysicsParams{}, 7);
  const PhysicsPile pile = bin.drop(5);
  ASSERT_TRUE(pile.settled);
  ASSERT_EQ(bin.size(), 5);
  const std::vector<Eigen::Isometry3d> before = bin.poses();
  const auto [supported, support] = topAndSupport(part, before);
  ASSERT_GT(lowestZ(part, before[supported]), 0.03) << "the boxes did not stack";

  const SettleResult result = bin.remove(support);
  EXPECT_TRUE(result.settled);
  EXPECT_GT(result.steps, 0);
  EXPECT_LE(result.simulated_time, PhysicsParams{}.max_resettle_time);
  EXPECT_TRUE(result.escaped.empty());
  const std::vector<Eigen::Isometry3d> after = bin.poses();
  ASSERT_EQ(after.size(), 4u);
  // The order is kept with the removed part left out.
  const int moved_index = supported > support ? supported - 1 : supported;
  const double drop_mm = 1e3 * (lowestZ(part, before[supported]) - lowestZ(part, after[moved_index]));
  EXPECT_GT(drop_mm, 5.0) << "the part above stayed in the air";
}

TEST(PhysicsBin, RemovingEveryPartEmptiesTheBin) {
  const io::TriangleMesh part = flatBox();
  PhysicsBin bin(part, kNarrowBin, PhysicsParams{}, 3);
  bin.drop(5);
  int removed = 0;
  while (bin.size() > 0) {
    const std::vector<Eigen::Isometry3d> poses = bin.poses();
    // Always the topmost part, as a robot would: the rest stays inside and settles.
    int top = 0;
    for (int i = 1; i < bin.size(); ++i) {
      if (lowestZ(part, poses[i]) > lowestZ(part, poses[top])) top = i;
    }
    const SettleResult result = bin.remove(top);
    EXPECT_TRUE(result.settled);
    EXPECT_TRUE(result.escaped.empty());
    ++removed;
    ASSERT_LE(removed, 5);
  }
  EXPECT_EQ(removed, 5);
  EXPECT_TRUE(bin.poses().empty());
  EXPECT_THROW(bin.remove(0), core::Error);
}

TEST(PhysicsBin, SameCallsGiveBitIdenticalPoses) {
  const io::TriangleMesh part = flatBox();
  PhysicsBin first(part, kNarrowBin, PhysicsParams{}, 11);
  PhysicsBin second(part, kNarrowBin, PhysicsParams{}, 11);
  first.drop(4);
  second.drop(4);
  first.remove(0);
  second.remove(0);
  const auto a = first.poses(), b = second.poses();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i].matrix() == b[i].matrix()) << i;
}

TEST(PhysicsBin, RejectsBadInput) {
  const io::TriangleMesh part = flatBox();
  EXPECT_THROW(PhysicsBin(part, BinInterior{0.02, 0.02, 0.1}, PhysicsParams{}, 1), core::Error);
  PhysicsParams bad;
  bad.max_resettle_time = 0.0;
  EXPECT_THROW(PhysicsBin(part, kNarrowBin, bad, 1), core::Error);
  PhysicsBin bin(part, kNarrowBin, PhysicsParams{}, 1);
  EXPECT_THROW(bin.drop(-1), core::Error);
  bin.drop(1);
  EXPECT_THROW(bin.remove(1), core::Error);
  EXPECT_THROW(bin.remove(-1), core::Error);
}

// A quarter-resolution camera keeps the rendering fast; the geometry does not change.
PileParams smallView(int objects) {
  PileParams params;
  params.objects = objects;
  params.seed = 5;
  params.rig.camera = params.rig.camera.scaled(0.5);
  return params;
}

bool sameBits(const io::PointCloud& a, const io::PointCloud& b) {
  if (a.points.size() != b.points.size()) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const Eigen::Vector3f &p = a.points[i], &q = b.points[i];
    for (int k = 0; k < 3; ++k) {
      if (!(p[k] == q[k] || (std::isnan(p[k]) && std::isnan(q[k])))) return false;
    }
  }
  return true;
}

// The poses a pile settled at, viewed again, give the very scene generatePile gave.
TEST(PileView, ViewAtThePhysicsPosesIsTheGeneratedPile) {
  const io::TriangleMesh part = makePart("clamp").mesh;
  const PileParams params = smallView(6);
  const PileScene generated = generatePile(part, params);
  const PileScene viewed = viewPile(part, params, generated.physics.T_bin_object);
  ASSERT_EQ(viewed.objects.size(), generated.objects.size());
  for (std::size_t i = 0; i < viewed.objects.size(); ++i) {
    EXPECT_TRUE(viewed.objects[i].T_camera_object.matrix() == generated.objects[i].T_camera_object.matrix());
    EXPECT_EQ(viewed.objects[i].visible_pixels, generated.objects[i].visible_pixels);
    EXPECT_EQ(viewed.objects[i].unoccluded_pixels, generated.objects[i].unoccluded_pixels);
  }
  EXPECT_EQ(viewed.instance, generated.instance);
  EXPECT_TRUE(sameBits(viewed.cloud, generated.cloud));
  EXPECT_TRUE(sameBits(viewed.exact_cloud, generated.exact_cloud));
  EXPECT_TRUE(viewed.T_camera_bin.matrix() == generated.T_camera_bin.matrix());
}

TEST(PileView, EmptyBinShowsTheBinOnly) {
  const PileParams params = smallView(0);
  const PileCapture capture =
      renderPileCaptureAt(makePart("clamp").mesh, params, {}, io::PatternSetSpec{}, PhotometryParams{});
  EXPECT_TRUE(capture.scene.objects.empty());
  EXPECT_FALSE(capture.images.empty());
  int bin_pixels = 0;
  for (const int32_t id : capture.scene.instance) {
    EXPECT_LT(id, 0);
    bin_pixels += id == -2;
  }
  EXPECT_GT(bin_pixels, static_cast<int>(capture.scene.instance.size()) / 4);
}

// A part placed by hand appears where it was put: its pixels lie around its projected centre.
TEST(PileView, PartAppearsAtItsGivenPose) {
  const PileParams params = smallView(0);
  Eigen::Isometry3d T_bin_object = Eigen::Isometry3d::Identity();
  T_bin_object.translation() = Eigen::Vector3d(0.08, -0.05, 0.02);
  const PileScene scene = viewPile(makePart("clamp").mesh, params, {T_bin_object});
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_GT(scene.objects[0].visible_pixels, 50);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (std::size_t i = 0; i < scene.instance.size(); ++i) {
    if (scene.instance[i] != 0) continue;
    sum += scene.exact_cloud.points[i].cast<double>();
    ++count;
  }
  ASSERT_GT(count, 0);
  const Eigen::Vector3d centre_in_bin = scene.T_camera_bin.inverse() * (sum / count);
  EXPECT_LT(1e3 * (centre_in_bin.head<2>() - T_bin_object.translation().head<2>()).norm(), 15.0);
}

TEST(BinMesh, IsTheClosedBinAroundTheInterior) {
  const io::TriangleMesh mesh = binMesh(BinInterior{0.3, 0.2, 0.1});
  EXPECT_EQ(test::closedManifoldProblem(mesh), "");
  const test::PlacedMesh placed = test::place(mesh, Eigen::Isometry3d::Identity());
  EXPECT_NEAR(placed.box.max().z(), 0.1, 1e-6);
  EXPECT_NEAR(placed.box.max().x(), 0.16, 1e-6);  // the 10 mm wall outside the interior
  EXPECT_THROW(binMesh(BinInterior{0.3, -0.2, 0.1}), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
