// planPicks: the base-frame pose, tilt limit, choice among grasps, avoided objects, bad
// detections and both pick orders.
#include <gtest/gtest.h>

#include <limits>

#include "picking_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<int> pickedObjects(const PickPlan& plan) {
  std::vector<int> objects;
  for (const Pick& pick : plan.picks) objects.push_back(pick.object);
  return objects;
}

TEST(PickingPlanner, BasePoseMatchesAHandComputedOne) {
  PickParams params;
  params.grasps = {{"offset", pose({0.01, 0, 0.02}, rotX(180))}};
  const PickPlan plan = planPicks({part({0.05, -0.03, 0.08}, rotZ(30))}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  // Position: (50, -30, 80) mm + Rz(30) (10, 0, 20) mm. Axes: Rz(30) Rx(180).
  Eigen::Matrix4d expected;
  expected << 0.8660254, 0.5, 0, 0.0586603,  //
      0.5, -0.8660254, 0, -0.025,            //
      0, 0, -1, 0.10,                        //
      0, 0, 0, 1;
  EXPECT_TRUE(samePose(plan.picks[0].T_base_grasp, Eigen::Isometry3d(expected), 1e-3, 1e-3));
  EXPECT_EQ(plan.picks[0].object, 0);
  EXPECT_EQ(plan.picks[0].grasp, 0);
  EXPECT_NEAR(plan.picks[0].tilt_deg, 0.0, 1e-6);
}

TEST(PickingPlanner, ApproachSteeperThanMaxTiltIsRejected) {
  PickParams params = topGraspParams();
  const DetectedPart leaning = part({0, 0, 0.06}, rotY(50));
  params.max_tilt_deg = 50.001;
  const PickPlan plan = planPicks({leaning}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_NEAR(plan.picks[0].tilt_deg, 50.0, 1e-6);
  params.max_tilt_deg = 49.999;
  const PickPlan too_steep = planPicks({leaning}, {}, params);
  EXPECT_TRUE(too_steep.picks.empty());
  EXPECT_EQ(too_steep.rejected.tilt, 1);
  EXPECT_EQ(too_steep.rejected.total(), 1);
}

TEST(PickingPlanner, LeastTiltWinsThenTheLowestGraspIndex) {
  PickParams params;
  // "top_again" holds the tool's x axis along base +x, "top" 60 degrees off it: the grasp
  // index decides before the wrist angle.
  params.grasps = {{"leaning", pose({0, 0, 0.02}, rotY(20) * rotX(180))},
                   {"top", pose({0.01, 0, 0.02}, rotZ(60) * rotX(180))},
                   {"top_again", pose({-0.01, 0, 0.02}, rotX(180))}};
  const PickPlan plan = planPicks({part({0, 0, 0.05})}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  EXPECT_EQ(plan.picks[0].grasp, 1);
  // Leaning the part 20 degrees the other way makes the first grasp vertical: it wins.
  const PickPlan leaning = planPicks({part({0, 0, 0.05}, rotY(-20))}, {}, params);
  ASSERT_TRUE(picksOne(leaning));
  EXPECT_EQ(leaning.picks[0].grasp, 0);
  EXPECT_NEAR(leaning.picks[0].tilt_deg, 0.0, 1e-6);
}

TEST(PickingPlanner, ObjectsNearAFailedPickAreAvoided) {
  const PickParams params = topGraspParams();  // avoid_radius 20 mm
  const std::vector<DetectedPart> parts = {part({-0.05, 0, 0.05}), part({0.05, 0, 0.05})};
  const PickPlan plan = planPicks(parts, {{-0.035, 0, 0.05}}, params);  // 15 mm from part 0
  EXPECT_EQ(pickedObjects(plan), std::vector<int>{1});
  EXPECT_EQ(plan.rejected.avoided, 1);
  const PickPlan far = planPicks(parts, {{-0.025, 0, 0.05}}, params);  // 25 mm away
  EXPECT_EQ(far.picks.size(), 2u);
  EXPECT_EQ(far.rejected.avoided, 0);
}

// Grasp heights and scores with ties in each key; parts spread along x.
std::vector<DetectedPart> partsForOrdering() {
  const double heights[] = {0.05, 0.07, 0.05, 0.05, 0.07};
  const double scores[] = {0.8, 0.5, 0.9, 0.8, 0.8};
  std::vector<DetectedPart> parts;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector3d origin(-0.12 + 0.06 * i, 0, heights[i]);
    parts.push_back(part(origin, Eigen::Matrix3d::Identity(), scores[i]));
  }
  return parts;
}

TEST(PickingPlanner, HighestFirstOrdersByHeightThenScoreThenIndex) {
  PickParams params = topGraspParams();
  params.order = PickOrder::HighestFirst;
  const PickPlan plan = planPicks(partsForOrdering(), {}, params);
  EXPECT_EQ(pickedObjects(plan), (std::vector<int>{4, 1, 2, 0, 3}));
}

TEST(PickingPlanner, BestScoreOrdersByScoreThenHeightThenIndex) {
  PickParams params = topGraspParams();
  params.order = PickOrder::BestScore;
  const PickPlan plan = planPicks(partsForOrdering(), {}, params);
  EXPECT_EQ(pickedObjects(plan), (std::vector<int>{2, 4, 0, 3, 1}));
}

TEST(PickingPlanner, InvalidDetectionsAreSkippedAndCounted) {
  const PickParams params = topGraspParams();
  std::vector<DetectedPart> parts(6, part({0, 0, 0.05}));
  parts[0].T_base_model.translation().x() = kNaN;
  parts[1].T_base_model.linear()(1, 2) = std::numeric_limits<double>::infinity();
  parts[2].T_base_model.linear() *= 2.0;  // a scale, not a rotation
  parts[3].score = kNaN;
  parts[4].coverage = kNaN;
  const PickPlan plan = planPicks(parts, {{kNaN, 0, 0}}, params);
  EXPECT_EQ(pickedObjects(plan), std::vector<int>{5});
  EXPECT_EQ(plan.rejected.invalid, 5);
  EXPECT_EQ(plan.rejected.total(), 5);
}

TEST(PickingPlanner, NoDetectionsGiveAnEmptyPlan) {
  const PickPlan plan = planPicks({}, {}, topGraspParams());
  EXPECT_TRUE(plan.picks.empty());
  EXPECT_EQ(plan.rejected.total(), 0);
}

TEST(PickingPlanner, BadParamsThrowNamingTheField) {
  PickParams params = topGraspParams();
  params.gripper.tool_radius = -0.01;
  EXPECT_TRUE(binpick::test::throwsNaming(
      [&] {
        planPicks({part({0, 0, 0.05})}, {}, params);
      },
      "picking.gripper.tool_radius"));
}

}  // namespace
}  // namespace binpick::picking
