// PickParams::validate and pickOrderFromName: bad configuration throws naming the field.
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "picking_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;
using binpick::test::throwsNaming;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Validates topGraspParams() after `spoil`; the message must name `field`.
::testing::AssertionResult rejects(const std::function<void(PickParams&)>& spoil, const std::string& field) {
  PickParams params = topGraspParams();
  spoil(params);
  return throwsNaming([&] { params.validate(); }, "picking." + field + " must be");
}

TEST(PickingParams, DefaultsWithAGraspAreValid) {
  EXPECT_NO_THROW(topGraspParams().validate());
  PickParams with_axis = topGraspParams();
  with_axis.symmetry.continuous_axis = Eigen::Vector3d(1, 1, 0);
  with_axis.symmetry.discrete = {rotX(180), rotZ(0)};
  EXPECT_NO_THROW(with_axis.validate());
}

TEST(PickingParams, GraspsMustBeGivenAndRigid) {
  EXPECT_TRUE(rejects([](PickParams& p) { p.grasps.clear(); }, "grasps"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.grasps[0].T_model_grasp.translation().x() = kNaN; }, "grasps"));
  PickParams scaled = topGraspParams();
  scaled.grasps[0].T_model_grasp.linear() *= 1.1;
  EXPECT_TRUE(throwsNaming([&] { scaled.validate(); }, "(got top)"));  // names the grasp
}

TEST(PickingParams, SymmetriesMustBeRotationsHoldingTheIdentity) {
  EXPECT_TRUE(rejects([](PickParams& p) { p.symmetry.discrete.clear(); }, "symmetry.discrete"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.symmetry.discrete.push_back(Eigen::Vector3d(1, 1, -1).asDiagonal()); },
                      "symmetry.discrete"));  // a mirror
  EXPECT_TRUE(rejects([](PickParams& p) { p.symmetry.discrete = {rotZ(90), rotZ(270)}; }, "symmetry.discrete"));
  EXPECT_TRUE(
      rejects([](PickParams& p) { p.symmetry.continuous_axis = Eigen::Vector3d::Zero(); }, "symmetry.continuous_axis"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.symmetry.continuous_axis = Eigen::Vector3d(kNaN, 0, 1); },
                      "symmetry.continuous_axis"));
}

TEST(PickingParams, BinMustBeARigidPoseAndPositiveSizes) {
  EXPECT_TRUE(rejects([](PickParams& p) { p.bin.T_base_bin.linear() *= 0.5; }, "bin.T_base_bin"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.bin.length = 0; }, "bin.length"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.bin.width = kNaN; }, "bin.width"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.bin.wall_height = -0.1; }, "bin.wall_height"));
}

TEST(PickingParams, DistancesAnglesAndStepsMustBeInRange) {
  EXPECT_TRUE(rejects([](PickParams& p) { p.approach_distance = -0.01; }, "approach_distance"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.gripper.tool_radius = kNaN; }, "gripper.tool_radius"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.gripper.cup_diameter = 0; }, "gripper.cup_diameter"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.wall_clearance = -0.001; }, "wall_clearance"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.max_tilt_deg = 181; }, "max_tilt_deg"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.max_tilt_deg = -1; }, "max_tilt_deg"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.continuous_symmetry_steps = 0; }, "continuous_symmetry_steps"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.continuous_symmetry_steps = 4000; }, "continuous_symmetry_steps"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.avoid_radius = -0.02; }, "avoid_radius"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.collision_margin = -0.001; }, "collision_margin"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.finger_clearance = kNaN; }, "finger_clearance"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.clearance_cap = 0; }, "clearance_cap"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.cover_radius = -0.04; }, "cover_radius"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.cover_height = kNaN; }, "cover_height"));
}

TEST(PickingParams, RankingWeightsAndGraspQualityMustBeInRange) {
  EXPECT_TRUE(rejects([](PickParams& p) { p.ranking.free = -1; }, "ranking.free"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.ranking.clearance = kNaN; }, "ranking.clearance"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.ranking.quality = -0.5; }, "ranking.quality"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.grasps[0].quality = 1.5; }, "grasps"));
  EXPECT_TRUE(rejects([](PickParams& p) { p.grasps[0].width = -0.01; }, "grasps"));
}

TEST(PickingParams, PickOrderNames) {
  EXPECT_EQ(pickOrderFromName("highest_first"), PickOrder::HighestFirst);
  EXPECT_EQ(pickOrderFromName("best_score"), PickOrder::BestScore);
  EXPECT_EQ(pickOrderFromName("best_rank"), PickOrder::BestRank);
  EXPECT_TRUE(throwsNaming([] { pickOrderFromName("lowest_first"); }, "\"lowest_first\""));
}

}  // namespace
}  // namespace binpick::picking
