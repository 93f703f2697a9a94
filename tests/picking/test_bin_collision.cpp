// The approach corridor against the bin (picking.hpp): walls, wall top, floor, a moved bin.
// Default bin: inner half sizes 200 x 150 mm, walls 150 mm high; with the 25 mm tool these tests
// set and the default 5 mm clearance the corridor radius is 30 mm, so a grasp point below the wall
// top must stay within 170 x 120 mm of the centre.
#include <gtest/gtest.h>

#include <cmath>

#include "picking_test_support.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

// The default top grasp's part placed so that its grasp point lands on `grasp_point`.
DetectedPart partGraspedAt(const Eigen::Vector3d& grasp_point) {
  return part(grasp_point - Eigen::Vector3d(0, 0, 0.02));
}

// The top grasp with the tool the limits below are worked out for, straight (leaning tests
// set their own max_lean_deg).
PickParams wideToolParams() {
  PickParams params = topGraspParams();
  params.gripper.tool_radius = 0.025;
  params.gripper.max_lean_deg = 0;
  return params;
}

PickParams leaningToolParams(double max_lean_deg = 6) {
  PickParams params = wideToolParams();
  params.gripper.max_lean_deg = max_lean_deg;
  return params;
}

bool reachable(const PickParams& params, const DetectedPart& detected) {
  return planPicks({detected}, {}, params).picks.size() == 1;
}

TEST(PickingBin, VerticalGraspNearAWallIsRejectedInTheCentreAccepted) {
  const PickParams params = wideToolParams();
  EXPECT_FALSE(reachable(params, partGraspedAt({0.185, 0, 0.06})));
  EXPECT_FALSE(reachable(params, partGraspedAt({0, -0.135, 0.06})));
  EXPECT_TRUE(reachable(params, partGraspedAt({0, 0, 0.06})));
}

// Analytic, not sampled: 1 mm either side of each limit decides.
TEST(PickingBin, VerticalCorridorLimitsHoldToTheMillimetre) {
  const PickParams params = wideToolParams();
  EXPECT_TRUE(reachable(params, partGraspedAt({0.169, 0, 0.06})));
  EXPECT_FALSE(reachable(params, partGraspedAt({0.171, 0, 0.06})));
  EXPECT_TRUE(reachable(params, partGraspedAt({0, -0.119, 0.06})));
  EXPECT_FALSE(reachable(params, partGraspedAt({0, -0.121, 0.06})));
}

// The 6 mm cup is narrower than the body: 10 mm from the wall it fits (3 mm + 5 mm clearance)
// once the body, 25 mm behind the grasp point, is above the wall top; 7 mm from it it does not.
TEST(PickingBin, BesideTheWallOnlyTheCupMustFitBelowTheWallTop) {
  PickParams params = wideToolParams();
  EXPECT_TRUE(reachable(params, partGraspedAt({0.19, 0, 0.126})));
  EXPECT_FALSE(reachable(params, partGraspedAt({0.19, 0, 0.124})));
  EXPECT_FALSE(reachable(params, partGraspedAt({0.193, 0, 0.149})));
  // Jaws closing along the wall, 15 mm from it: the body's width all the way down, so free only
  // once the grasp point is above the wall top (the fingers' corridors fit below it).
  params.gripper.type = GripperType::Parallel;
  const auto jawsAt = [](double z) { return part({0.185, 0, z - 0.02}, rotZ(90)); };
  EXPECT_FALSE(reachable(params, jawsAt(0.149)));
  EXPECT_TRUE(reachable(params, jawsAt(0.151)));
}

// A flat part on the floor 2 mm too close to the +x wall for a straight approach: the body's
// lowest slice, 25 mm behind the grasp point, clears once the approach leans by asin(2 / 25) =
// 4.6 degrees away from the wall, so the first whole degree that does is 5.
TEST(PickingBin, ASuctionToolBesideAWallLeansAwayFromIt) {
  PickParams params = leaningToolParams();
  const DetectedPart by_the_wall = partGraspedAt({0.172, 0, 0.02});
  const PickPlan plan = planPicks({by_the_wall}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  const Pick& pick = plan.picks[0];
  EXPECT_NEAR(pick.lean_deg, 5.0, 1e-6);
  EXPECT_NEAR(pick.tilt_deg, 5.0, 1e-6);
  EXPECT_LT((pick.T_base_grasp.translation() - Eigen::Vector3d(0.172, 0, 0.02)).norm(), 1e-9);  // same point
  EXPECT_GT(pick.T_base_grasp.linear().col(2).x(), 0.0);  // the approach towards the wall, the tool's back away
  EXPECT_NEAR(pick.T_base_grasp.linear().col(2).y(), 0.0, 1e-9);

  EXPECT_FALSE(reachable(leaningToolParams(4), by_the_wall));
  // 25 mm * sin(6) = 2.6 mm: no further
  EXPECT_FALSE(reachable(params, partGraspedAt({0.1727, 0, 0.02})));
  params.gripper.type = GripperType::Parallel;  // jaws never lean
  EXPECT_FALSE(reachable(params, by_the_wall));
}

// In a corner the tool leans along the diagonal: 1.5 mm too close to both walls needs
// asin(1.5 * sqrt(2) / 25) = 4.9 degrees.
TEST(PickingBin, InACornerTheToolLeansAlongTheDiagonal) {
  const PickPlan plan = planPicks({partGraspedAt({0.1715, -0.1215, 0.02})}, {}, leaningToolParams());
  ASSERT_TRUE(picksOne(plan));
  EXPECT_NEAR(plan.picks[0].lean_deg, 5.0, 1e-6);
  const Eigen::Vector3d approach = plan.picks[0].T_base_grasp.linear().col(2);
  EXPECT_NEAR(approach.x(), -approach.y(), 1e-9);
  EXPECT_GT(approach.x(), 0.0);
}

// Approach 45 degrees off vertical, from +x: the pre-grasp point lies 70.7 mm further out in x
// and up in z than the grasp point.
PickParams leaningGraspParams() {
  PickParams params = wideToolParams();
  params.grasps = {{"leaning", pose({0, 0, 0.02}, rotY(45) * rotX(180))}};
  return params;
}

TEST(PickingBin, CorridorCrossingTheWallTopIsRejected) {
  const PickParams params = leaningGraspParams();
  // Grasp point 30 mm inside the shrunk box, but the corridor leaves over the +x wall top.
  EXPECT_FALSE(reachable(params, partGraspedAt({0.14, 0, 0.12})));
  EXPECT_TRUE(reachable(params, partGraspedAt({0, 0, 0.12})));
  // As close to the -x wall, the corridor leans towards the centre: free.
  EXPECT_TRUE(reachable(params, partGraspedAt({-0.14, 0, 0.12})));
}

// A tilted corridor's slice reaches 30 mm * sin(45) below its axis: every slice whose axis is
// below 150 + 21.2 mm must have it within 170 mm of the centre in x. Along the corridor x grows
// as z does, so from a grasp point at z = 120 mm the limit is x = 170 - 51.2 mm.
TEST(PickingBin, TiltedCorridorLimitHoldsToTheMillimetre) {
  const PickParams params = leaningGraspParams();
  const double radius = params.gripper.tool_radius + params.wall_clearance;
  const double checked_up_to = params.bin.wall_height + radius * std::sin(radians(45));
  const double limit_x = 0.5 * params.bin.length - radius - (checked_up_to - 0.12);
  EXPECT_TRUE(reachable(params, partGraspedAt({limit_x - 0.001, 0, 0.12})));
  EXPECT_FALSE(reachable(params, partGraspedAt({limit_x + 0.001, 0, 0.12})));
}

// A thin part lying on the floor is pickable: only the corridor's axis must stay above it.
TEST(PickingBin, GraspPointJustAboveTheFloorIsAcceptedBelowItRejected) {
  PickParams params;
  params.grasps = {{"flat", pose({0, 0, 0.002}, rotX(180))}};
  EXPECT_TRUE(reachable(params, part({0, 0, 0})));
  EXPECT_FALSE(reachable(params, part({0, 0, -0.003})));
}

TEST(PickingBin, ApproachFromBelowTheFloorIsRejected) {
  PickParams params = wideToolParams();
  params.max_tilt_deg = 180;
  const DetectedPart upside_down = part({0, 0, 0.05}, rotX(180));  // grasp point 30 mm up
  EXPECT_FALSE(reachable(params, upside_down));                    // pre-grasp point 70 mm below the floor
  params.approach_distance = 0.005;
  params.gripper.cup_length = 0.01;
  params.gripper.tool_length = 0.01;
  EXPECT_TRUE(reachable(params, upside_down));  // the tool's end 5 mm above the floor at the pre-grasp point
}

// Tilted 50 degrees towards the +x wall from a grasp point 50 mm off the centre, 30 mm up: the
// pre-grasp point (100 mm out) stays within the corridor's 170 mm, but the body behind it (25 mm
// of cup and 150 mm of tool) swings out to x = 220 mm below the wall top.
TEST(PickingBin, ATiltedToolsBodySwingsOverTheWallBeyondThePreGraspPoint) {
  PickParams params = wideToolParams();
  const Eigen::Matrix3d tilt = rotY(50);
  const DetectedPart tilted = part(Eigen::Vector3d(0.05, 0, 0.03) - tilt * Eigen::Vector3d(0, 0, 0.02), tilt);
  EXPECT_FALSE(reachable(params, tilted));
  params.gripper.tool_length = 0.02;  // the end of the body at x = 161 mm
  EXPECT_TRUE(reachable(params, tilted));
}

// The same face with a 45-degree bent nose: the wrist turns the body back from the face's normal
// towards vertical, 5 degrees from it, leaning towards +x; the cup still meets the face square.
TEST(PickingBin, ABentNoseTurnsItsBodyUprightOffAFaceTiltedTowardsAWall) {
  PickParams params = wideToolParams();
  params.gripper.nose_angle_deg = 45.0;
  const Eigen::Matrix3d tilt = rotY(50);
  const DetectedPart tilted = part(Eigen::Vector3d(0.05, 0, 0.03) - tilt * Eigen::Vector3d(0, 0, 0.02), tilt);
  const PickPlan plan = planPicks({tilted}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  const Pick& pick = plan.picks[0];
  EXPECT_NEAR(pick.tilt_deg, 50.0, 1e-6);
  EXPECT_NEAR(pick.lean_deg, 0.0, 1e-9);
  const Eigen::Vector3d body = pick.T_base_grasp.linear() * params.gripper.bodyAxis();
  EXPECT_NEAR(degrees(std::acos(body.z())), 5.0, 1e-6);
  EXPECT_GT(body.x(), 0.0);
  EXPECT_NEAR(body.y(), 0.0, 1e-9);
  params.gripper.nose_angle_deg = 30.0;  // 20 degrees towards the wall: its end clears it too
  EXPECT_TRUE(reachable(params, tilted));
  params.gripper.nose_angle_deg = 10.0;  // 40 degrees: the body swings over the wall
  EXPECT_FALSE(reachable(params, tilted));
}

// Jaws opened to a 50 mm part + 5 mm each side: each 8 x 12 mm finger's axis stands 34 mm off the
// grasp point along the closing axis, its corridor 7.2 + 5 mm in radius, so its axis must stay
// within 187.8 mm of the centre along the bin (137.8 across). 160 mm along the bin the body
// clears the +x wall (170 mm); closing along x the +x finger's axis is at 194 mm; turned a
// quarter, closing along the wall, the fingers clear it.
TEST(PickingBin, JawsFingersAreCheckedAgainstTheWalls) {
  PickParams params = wideToolParams();
  params.gripper.type = GripperType::Parallel;
  params.grasps = {{"across", pose({0, 0, 0.02}, rotX(180)), 1.0, 0.050}};
  EXPECT_FALSE(reachable(params, partGraspedAt({0.16, 0, 0.03})));
  const DetectedPart turned = part({0.16, 0, 0.01}, rotZ(90));
  EXPECT_TRUE(reachable(params, turned));
  // 100 mm across the bin, closing across it: 134 mm for a 50 mm part, 144 mm at the full stroke.
  const DetectedPart across = part({0.0, 0.10, 0.01}, rotZ(90));
  EXPECT_TRUE(reachable(params, across));
  params.grasps[0].width = 0.0;  // unknown width: opened to the whole 80 mm stroke
  EXPECT_FALSE(reachable(params, across));
}

// The bin turned a quarter about base z (its length along base y), tilted 10 degrees and moved:
// limits hold in the bin frame, and the pick is the bin-frame grasp carried into the base.
TEST(PickingBin, MovedAndTiltedBinChecksInItsOwnFrame) {
  PickParams params = wideToolParams();
  params.bin.T_base_bin = pose({0.8, -0.2, 0.3}, rotZ(90) * rotX(10));
  const auto inBin = [&params](const Eigen::Vector3d& grasp_point_in_bin) {
    return DetectedPart{params.bin.T_base_bin * partGraspedAt(grasp_point_in_bin).T_base_model, 1};
  };
  EXPECT_TRUE(reachable(params, inBin({0.16, 0, 0.06})));   // within 170 mm along the length
  EXPECT_FALSE(reachable(params, inBin({0, 0.13, 0.06})));  // beyond 120 mm across the width
  EXPECT_TRUE(reachable(params, inBin({0, 0.13, 0.16})));   // above the wall top
  EXPECT_FALSE(reachable(params, inBin({0, 0, -0.001})));   // below the floor

  const PickPlan plan = planPicks({inBin({0.16, 0.05, 0.06})}, {}, params);
  ASSERT_TRUE(picksOne(plan));
  const Eigen::Isometry3d expected = params.bin.T_base_bin * pose({0.16, 0.05, 0.06}, rotX(180));
  EXPECT_TRUE(samePose(plan.picks[0].T_base_grasp, expected, 1e-3, 1e-3));
  EXPECT_NEAR(plan.picks[0].tilt_deg, 10.0, 1e-6);
}

}  // namespace
}  // namespace binpick::picking
