// planPicks with a measured scene: cover, the cloud test, rejections by reason, the ranking value
// and its order; a full-size cloud with 20 parts for the planning time.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "binpick/core/stopwatch.hpp"
#include "binpick/picking/tool_collision.hpp"
#include "measured_scene_support.hpp"
#include "picking_test_support.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

std::vector<int> pickedObjects(const PickPlan& plan) {
  std::vector<int> objects;
  for (const Pick& pick : plan.picks) objects.push_back(pick.object);
  return objects;
}

// The default top grasp's part with its top (the grasp point) at `top`, and that top in the cloud.
DetectedPart partWithTop(const Eigen::Vector3d& top, CloudBuilder& cloud) {
  cloud.slab(top.x() - 0.015, top.x() + 0.015, top.y() - 0.015, top.y() + 0.015, top.z());
  return part(top - Eigen::Vector3d(0, 0, 0.02));
}

TEST(PickingRanking, APartCoveredByAnotherPartsPointsLosesToAFreeOne) {
  CloudBuilder cloud;
  cloud.slab(-0.19, 0.19, -0.14, 0.14, 0.0);  // the floor
  const std::vector<DetectedPart> parts = {partWithTop({-0.08, 0, 0.07}, cloud), partWithTop({0.08, 0, 0.07}, cloud)};
  PickParams params = topGraspParams();
  params.gripper.tool_radius = 0.025;
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params, nullptr)), (std::vector<int>{0, 1}));
  const MeasuredScene uncovered = cloud.scene();
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params, &uncovered)), (std::vector<int>{0, 1}));  // a tie

  // A neighbour lying across part 0's edge, 30 mm above its top: clear of the tool's body
  // (radius 27 mm with the margin) but over the part.
  CloudBuilder covered = cloud;
  covered.slab(-0.08 + 0.03, -0.08 + 0.045, -0.04, 0.04, 0.10);
  const MeasuredScene scene = covered.scene();
  const PickPlan plan = planPicks(parts, {}, params, &scene);
  ASSERT_EQ(pickedObjects(plan), (std::vector<int>{1, 0}));
  EXPECT_LT(plan.picks[1].rank, plan.picks[0].rank);
  EXPECT_NEAR(plan.picks[1].clearance, 0.003, 1e-4);  // 30 mm from the axis
  EXPECT_NEAR(plan.picks[0].clearance, 0.02, 1e-9);
  // The cover alone decides too, with the clearance out of the ranking.
  params.ranking.clearance = 0.0;
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params, &scene)), (std::vector<int>{1, 0}));
}

// Each grasp counted by the furthest test any of its grasps reached.
TEST(PickingRanking, RejectionsAreCountedByReason) {
  PickParams params = topGraspParams();
  params.grasps.push_back({"steep", pose({0, 0, 0.02}, rotY(70) * rotX(180))});  // always > 60 deg
  CloudBuilder cloud;
  const DetectedPart tilted = part({0, -0.08, 0.05}, rotY(90));         // top 90, steep 160 degrees
  const DetectedPart at_wall = part({0.185, 0, 0.04});                  // top hits the wall
  const DetectedPart buried = partWithTop({-0.08, 0.05, 0.07}, cloud);  // top hits the cloud
  const DetectedPart free = partWithTop({0.05, 0.05, 0.07}, cloud);
  cloud.point(-0.08 + 0.003, 0.05, 0.075);  // 5 mm above the buried part's grasp point, in the cup
  const MeasuredScene scene = cloud.scene();

  const PickPlan plan = planPicks({tilted, at_wall, buried, free}, {}, params, &scene);
  EXPECT_EQ(pickedObjects(plan), std::vector<int>{3});
  EXPECT_EQ(plan.rejected.tilt, 1);
  EXPECT_EQ(plan.rejected.bin, 1);
  EXPECT_EQ(plan.rejected.cloud, 1);
  EXPECT_EQ(plan.rejected.total(), 3);

  const PickPlan without_cloud = planPicks({tilted, at_wall, buried, free}, {}, params);
  EXPECT_EQ(without_cloud.picks.size(), 2u);
  EXPECT_EQ(without_cloud.rejected.cloud, 0);
}

TEST(PickingRanking, ACollidingGraspGivesWayToTheNextOne) {
  PickParams params = topGraspParams();
  params.gripper.cup_diameter = 0.016;  // the cup reaches 10 mm from the axis with the margin
  params.gripper.tool_radius = 0.025;
  params.grasps.push_back({"other end", pose({0.03, 0, 0.02}, rotX(180))});
  CloudBuilder cloud;
  cloud.slab(-0.02, 0.05, -0.015, 0.015, 0.07);
  const DetectedPart detected = part({0, 0, 0.05});
  const MeasuredScene free_scene = cloud.scene();
  const PickPlan free = planPicks({detected}, {}, params, &free_scene);
  ASSERT_TRUE(picksOne(free));
  EXPECT_EQ(free.picks[0].grasp, 0);  // a tie: the lower index

  cloud.point(-0.006, 0, 0.075);  // inside the first grasp's cup, 36 mm from the second's axis
  const MeasuredScene scene = cloud.scene();
  const PickPlan plan = planPicks({detected}, {}, params, &scene);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_EQ(plan.picks[0].grasp, 1);
  EXPECT_FALSE(toolCollision(scene, plan.picks[0].T_base_grasp, params.gripper, {}).collision);
}

TEST(PickingRanking, RankingPrefersHigherCoverageAndLowerTilt) {
  PickParams params = topGraspParams();
  std::vector<DetectedPart> parts = {part({-0.05, 0, 0.05}), part({0.05, 0, 0.05})};
  parts[0].coverage = 0.6;
  parts[1].coverage = 0.9;
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params)), (std::vector<int>{1, 0}));
  params.order = PickOrder::HighestFirst;  // same height and score: the index decides
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params)), (std::vector<int>{0, 1}));

  // Tilted 30 and 10 degrees, the grasp points at the same height.
  params.order = PickOrder::BestRank;
  const auto leaning = [](double x, double tilt_deg) {
    return part({x, 0, 0.07 - 0.02 * std::cos(radians(tilt_deg))}, rotY(tilt_deg));
  };
  const PickPlan plan = planPicks({leaning(-0.05, 30), leaning(0.05, 10)}, {}, params);
  ASSERT_EQ(pickedObjects(plan), (std::vector<int>{1, 0}));
  EXPECT_NEAR(plan.picks[0].tilt_deg, 10.0, 1e-6);
}

// The documented sum (picking.hpp): free 2, height 1 (70 / 150 mm), coverage 1 (0.8), upright 1
// (tilt 0), clearance 0.5 (capped: no cloud), quality 1 (0.7).
TEST(PickingRanking, TheRankIsTheDocumentedWeightedSum) {
  PickParams params = topGraspParams();
  params.grasps[0].quality = 0.7;
  DetectedPart detected = part({0, 0, 0.05});
  detected.coverage = 0.8;
  const PickPlan plan = planPicks({detected}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_NEAR(plan.picks[0].rank, 2.0 + 0.07 / 0.15 + 0.8 + 1.0 + 0.5 + 0.7, 1e-9);
  EXPECT_NEAR(plan.picks[0].clearance, params.clearance_cap, 1e-12);
}

// A part the detector is not sure of (its turned twin explains the range nearly as well) comes
// after the sure ones, however well the planner ranks it; its rank itself stays what it was.
TEST(PickingRanking, APartTheDetectorIsNotSureOfIsPickedAfterTheSureOnes) {
  PickParams params = topGraspParams();
  // Part 0's top 40 mm higher and its coverage better: the higher rank.
  std::vector<DetectedPart> parts = {part({-0.05, 0, 0.09}), part({0.05, 0, 0.05}), part({0.0, 0.08, 0.07})};
  parts[0].coverage = 0.95;
  parts[1].coverage = 0.7;
  parts[2].coverage = 0.8;
  const PickPlan all_sure = planPicks(parts, {}, params);
  ASSERT_EQ(pickedObjects(all_sure), (std::vector<int>{0, 2, 1}));
  ASSERT_GT(all_sure.picks[0].rank, all_sure.picks[1].rank);

  parts[0].sure = false;
  const PickPlan plan = planPicks(parts, {}, params);
  ASSERT_EQ(pickedObjects(plan), (std::vector<int>{2, 1, 0}));
  EXPECT_EQ(plan.picks[2].rank, all_sure.picks[0].rank);
  EXPECT_EQ(plan.picks[2].T_base_grasp.matrix(), all_sure.picks[0].T_base_grasp.matrix());
  // Among the unsure ones the rank still decides.
  parts[2].sure = false;
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params)), (std::vector<int>{1, 0, 2}));

  // The explicit orders keep their one key.
  params.order = PickOrder::HighestFirst;
  EXPECT_EQ(pickedObjects(planPicks(parts, {}, params)), (std::vector<int>{0, 2, 1}));
}

// With every part sure (the default) the plan is what the rank alone gives, on a measured scene too.
TEST(PickingRanking, AllSurePartsArePlannedAsBefore) {
  CloudBuilder cloud;
  cloud.slab(-0.19, 0.19, -0.14, 0.14, 0.0);  // the floor
  std::vector<DetectedPart> parts = {partWithTop({-0.08, 0, 0.07}, cloud), partWithTop({0.08, 0, 0.09}, cloud),
                                     partWithTop({0.0, 0.07, 0.05}, cloud)};
  cloud.slab(-0.08 + 0.03, -0.08 + 0.045, -0.04, 0.04, 0.10);  // a neighbour over part 0
  const MeasuredScene scene = cloud.scene();
  const PickParams params = topGraspParams();
  const PickPlan by_default = planPicks(parts, {}, params, &scene);
  ASSERT_EQ(pickedObjects(by_default), (std::vector<int>{1, 2, 0}));
  for (DetectedPart& p : parts) p.sure = true;
  const PickPlan all_sure = planPicks(parts, {}, params, &scene);
  ASSERT_EQ(pickedObjects(all_sure), pickedObjects(by_default));
  for (std::size_t i = 0; i < all_sure.picks.size(); ++i) {
    EXPECT_EQ(all_sure.picks[i].rank, by_default.picks[i].rank);
    EXPECT_EQ(all_sure.picks[i].T_base_grasp.matrix(), by_default.picks[i].T_base_grasp.matrix());
  }
  // Ranked by the rank alone: descending.
  for (std::size_t i = 1; i < all_sure.picks.size(); ++i) EXPECT_GT(all_sure.picks[i - 1].rank, all_sure.picks[i].rank);
}

// ---- A full-size cycle: 1280 x 1024 pixels, 20 boxes on the floor ------------------------------

struct Block {
  Eigen::Vector2d centre;
  double top = 0.0;
};

std::vector<Block> randomBlocks(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-0.15, 0.15), y(-0.10, 0.10), top(0.02, 0.08);
  std::vector<Block> blocks;
  for (int i = 0; i < count; ++i) blocks.push_back({{x(rng), y(rng)}, top(rng)});
  return blocks;
}

// Camera 1 m above the bin looking down, 0.5 mm per pixel on the floor; 40 x 30 mm blocks.
io::PointCloud blockCloud(const std::vector<Block>& blocks, const Eigen::Isometry3d& T_base_camera) {
  io::PointCloud cloud;
  cloud.width = 1280;
  cloud.height = 1024;
  cloud.points.reserve(1280 * 1024);
  const Eigen::Isometry3d T_camera_base = T_base_camera.inverse();
  for (int row = 0; row < cloud.height; ++row) {
    for (int column = 0; column < cloud.width; ++column) {
      const Eigen::Vector2d xy((column - 640) * 0.0005, (row - 512) * 0.0005);
      double z = 0.0;
      for (const Block& block : blocks) {
        const Eigen::Vector2d offset = (xy - block.centre).cwiseAbs();
        if (offset.x() < 0.02 && offset.y() < 0.015) z = std::max(z, block.top);
      }
      cloud.points.emplace_back((T_camera_base * Eigen::Vector3d(xy.x(), xy.y(), z)).cast<float>());
    }
  }
  return cloud;
}

TEST(PickingRanking, TwentyPartsOnAFullSizeCloud) {
  const std::vector<Block> blocks = randomBlocks(20, 11);
  const Eigen::Isometry3d T_base_camera = pose({0, 0, 1.0}, rotX(180));
  const io::PointCloud cloud = blockCloud(blocks, T_base_camera);
  PickParams params = topGraspParams();
  params.grasps.push_back({"off centre", pose({0.01, 0, 0.02}, rotX(180))});
  params.symmetry.continuous_axis = Eigen::Vector3d::UnitZ();  // 2 x 36 candidates per part
  std::vector<DetectedPart> parts;
  for (const Block& block : blocks) parts.push_back(part({block.centre.x(), block.centre.y(), block.top - 0.02}));

  core::Stopwatch stopwatch;
  const MeasuredScene scene(cloud, T_base_camera);
  const double build_ms = stopwatch.lapMs();
  const PickPlan plan = planPicks(parts, {}, params, &scene);
  const double plan_ms = stopwatch.lapMs();
  RecordProperty("scene_build_ms", std::to_string(build_ms));
  RecordProperty("plan_ms", std::to_string(plan_ms));
  std::printf("measured scene: %zu points, built in %.1f ms; 20 parts x 72 grasps planned in %.2f ms\n", scene.size(),
              build_ms, plan_ms);

  ASSERT_FALSE(plan.picks.empty());
  EXPECT_EQ(plan.picks.size() + static_cast<std::size_t>(plan.rejected.total()), parts.size());
  for (std::size_t i = 0; i < plan.picks.size(); ++i) {
    const Pick& pick = plan.picks[i];
    EXPECT_FALSE(toolCollision(scene, pick.T_base_grasp, params.gripper, {}).collision) << "pick " << i;
    if (i > 0) {
      EXPECT_LE(pick.rank, plan.picks[i - 1].rank) << "pick " << i;
    }
  }
}

}  // namespace
}  // namespace binpick::picking
