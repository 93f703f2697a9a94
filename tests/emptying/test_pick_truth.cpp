#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/emptying/pick_truth.hpp"
#include "binpick/simulation/parts.hpp"

namespace binpick::emptying {
namespace {

constexpr double kPi = 3.14159265358979323846;
const simulation::BinInterior kBin;  // 400 x 300 mm, walls 150 mm high
constexpr double kApproach = 0.10;

struct Box {
  Eigen::Vector3d size;    // metres
  Eigen::Vector2d centre;  // on the floor, bin frame
};

// A box centred on its model origin. A TrueScene holds copies of one part, so each scene is made
// of equal boxes.
io::TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  const double x = 0.5 * size.x(), y = 0.5 * size.y();
  return simulation::makePrism({{-x, -y}, {x, -y}, {x, y}, {-x, y}}, size.z());
}

Eigen::Isometry3d onFloor(const Box& box) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(box.centre.x(), box.centre.y(), 0.5 * box.size.z());
  return pose;
}

// Identical boxes at the given centres.
TrueScene boxes(const Eigen::Vector3d& size, const std::vector<Eigen::Vector2d>& centres) {
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& c : centres) poses.push_back(onFloor({size, c}));
  return TrueScene(boxMesh(size), poses, kBin);
}

// Straight down onto (x, y, z): the grasp's z axis along the bin's -z.
Eigen::Isometry3d fromAbove(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

// A 16 mm cup, 25 mm long, on a 25 mm tool body 150 mm long: the geometry the cases below are
// laid out for.
picking::GripperParams suction() {
  picking::GripperParams gripper;
  gripper.type = picking::GripperType::Suction;
  gripper.cup_diameter = 0.016;
  gripper.cup_length = 0.025;
  gripper.tool_radius = 0.025;
  gripper.tool_length = 0.15;
  return gripper;
}

picking::GripperParams jaws() {
  picking::GripperParams gripper;
  gripper.type = picking::GripperType::Parallel;
  return gripper;
}

PickJudgement judge(const TrueScene& scene, const Eigen::Isometry3d& T_bin_grasp,
                    const picking::GripperParams& gripper) {
  return judgePick(scene, T_bin_grasp, gripper, kApproach, PickTruthParams{});
}

const Eigen::Vector3d kBlock(0.060, 0.060, 0.030);  // 60 x 60 mm, 30 mm high

TEST(SuctionTruth, CupCentredOnATopFaceHolds) {
  const TrueScene scene = boxes(kBlock, {{0.0, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.0, 0.0, 0.030), suction());
  EXPECT_TRUE(j.ok) << j.reason;
  EXPECT_EQ(j.reason, "");
  EXPECT_EQ(j.object, 0);
  EXPECT_NEAR(1e3 * j.distance, 0.0, 0.01);
  EXPECT_NEAR(j.angle_deg, 0.0, 0.01);
}

TEST(SuctionTruth, CupAFewMillimetresOffTheSurface) {
  const TrueScene scene = boxes(kBlock, {{0.0, 0.0}});
  const PickJudgement near = judge(scene, fromAbove(0.0, 0.0, 0.0315), suction());
  EXPECT_TRUE(near.ok) << near.reason;
  EXPECT_NEAR(1e3 * near.distance, 1.5, 0.01);  // the surface lies 1.5 mm ahead of the cup
  const PickJudgement far = judge(scene, fromAbove(0.0, 0.0, 0.034), suction());
  EXPECT_FALSE(far.ok);
  EXPECT_EQ(far.reason, "off the part");
  EXPECT_EQ(far.object, -1);
}

TEST(SuctionTruth, CupAcrossAnEdgeFails) {
  const TrueScene scene = boxes(kBlock, {{0.0, 0.0}});
  // The centre 3 mm inside the edge, the 8 mm cup hangs 5 mm over it.
  const PickJudgement j = judge(scene, fromAbove(0.027, 0.0, 0.030), suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "cup across an edge");
  EXPECT_EQ(j.object, -1);
  EXPECT_EQ(j.touched, 0);
}

TEST(SuctionTruth, CupOverAGapBetweenTwoBoxesFails) {
  // A 3 mm gap along x = 0 between two blocks.
  const TrueScene scene = boxes(kBlock, {{-0.0315, 0.0}, {0.0315, 0.0}});
  const PickJudgement beside = judge(scene, fromAbove(0.004, 0.0, 0.030), suction());
  EXPECT_FALSE(beside.ok);
  EXPECT_EQ(beside.reason, "cup over a gap");
  EXPECT_EQ(beside.touched, 1);
  const PickJudgement over = judge(scene, fromAbove(0.0, 0.0, 0.030), suction());
  EXPECT_FALSE(over.ok);
  EXPECT_EQ(over.reason, "off the part");
}

TEST(SuctionTruth, CupAcrossTwoTouchingBoxesIsOnANeighbour) {
  const TrueScene scene = boxes(kBlock, {{-0.030, 0.0}, {0.030, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.003, 0.0, 0.030), suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "cup on a neighbour");
}

// The pick was meant for part 0; the cup came down on part 1 and seals there: part 1 is lifted.
TEST(SuctionTruth, TheTruePartUnderTheCupIsTheOneHeld) {
  const TrueScene scene = boxes(kBlock, {{-0.050, 0.0}, {0.050, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.050, 0.005, 0.030), suction());
  EXPECT_TRUE(j.ok) << j.reason;
  EXPECT_EQ(j.object, 1);
}

TEST(SuctionTruth, AxisTiltedFifteenDegreesFails) {
  const TrueScene scene = boxes(kBlock, {{0.0, 0.0}});
  Eigen::Isometry3d T = fromAbove(0.0, 0.0, 0.030);
  T.linear() = Eigen::AngleAxisd(15.0 * kPi / 180.0, Eigen::Vector3d::UnitX()) * T.linear();
  const PickJudgement j = judge(scene, T, suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "tilted 15 deg from the surface");
  EXPECT_NEAR(j.angle_deg, 15.0, 0.01);
  // Within the limit the bellows takes the tilt: the face is flat under the whole disc.
  T.linear() = Eigen::AngleAxisd(-24.0 * kPi / 180.0, Eigen::Vector3d::UnitX()) * T.linear();
  const PickJudgement within = judge(scene, T, suction());
  EXPECT_TRUE(within.ok) << within.reason;
  EXPECT_NEAR(within.angle_deg, 9.0, 0.01);
}

TEST(SuctionTruth, TallNeighbourInTheToolsPathFails) {
  // Equal posts 20 x 20 x 100 mm: nine sunk into the floor to a 3 x 3 block 30 mm high (parts
  // 0-8, part 3 + k at x = 0, y = 20 k mm), and part 9 standing beside it, from x = 31 to 51 mm.
  const Eigen::Vector3d post(0.020, 0.020, 0.100);
  std::vector<Eigen::Isometry3d> posts;
  for (int i = -1; i <= 1; ++i) {
    for (int k = -1; k <= 1; ++k) {
      Eigen::Isometry3d sunk = Eigen::Isometry3d::Identity();
      sunk.translation() = Eigen::Vector3d(0.020 * i, 0.020 * k, 0.030 - 0.5 * post.z());
      posts.push_back(sunk);
    }
  }
  posts.push_back(onFloor({post, {0.041, 0.0}}));
  const TrueScene scene(boxMesh(post), posts, kBin);
  // On the far post the 25 mm body stays clear of part 9; on the near one it reaches x = 45 mm.
  const PickJudgement clear = judge(scene, fromAbove(-0.020, 0.0, 0.030), suction());
  EXPECT_TRUE(clear.ok) << clear.reason;
  EXPECT_EQ(clear.object, 1);
  const PickJudgement j = judge(scene, fromAbove(0.020, 0.0, 0.030), suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "tool hits part 9");
  EXPECT_EQ(j.obstacle, 9);
  EXPECT_EQ(j.touched, 7);
}

TEST(SuctionTruth, BinWallInTheToolsPathFails) {
  // A block against the +x wall (inner face at x = 200 mm): the 25 mm body centred 20 mm from
  // the wall reaches into it.
  const TrueScene scene = boxes(kBlock, {{0.169, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.180, 0.0, 0.030), suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "tool hits the bin");
  EXPECT_EQ(j.obstacle, PickJudgement::kBin);
  const PickJudgement away = judge(scene, fromAbove(0.160, 0.0, 0.030), suction());
  EXPECT_TRUE(away.ok) << away.reason;
}

// A bent nose's body leaves the approach axis at the back of the cup. Against the +x wall, 23 mm
// from the grasp point: the straight 25 mm body reaches it; bent 30 degrees away from the wall the
// body's lower rim reaches only 25 cos(30) = 21.7 mm that way; bent towards it, it hits.
TEST(SuctionTruth, ABentNosesBodyLeansWhereTheWristTurnsIt) {
  const TrueScene scene = boxes(kBlock, {{0.169, 0.0}});
  const Eigen::Isometry3d leaning_to_the_wall = fromAbove(0.177, 0.0, 0.030);  // grasp x = bin x
  Eigen::Isometry3d leaning_away = leaning_to_the_wall;
  leaning_away.linear() = leaning_to_the_wall.linear() * Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  EXPECT_EQ(judge(scene, leaning_to_the_wall, suction()).reason, "tool hits the bin");
  picking::GripperParams bent = suction();
  bent.nose_angle_deg = 30.0;
  const PickJudgement away = judge(scene, leaning_away, bent);
  EXPECT_TRUE(away.ok) << away.reason;
  EXPECT_EQ(judge(scene, leaning_to_the_wall, bent).reason, "tool hits the bin");
}

// A block tilted 50 degrees, its top face towards the +x wall: the straight tool's body, along the
// approach, meets the wall at the pose itself; a 45-degree bent nose turned upright stands 5
// degrees from vertical and clears it (a short approach: a longer one from over the wall would
// bring the cup's own path into it). Only the bent body's own columns are judged, none along the
// approach axis behind the cup.
TEST(SuctionTruth, ABentNosesBodyIsJudgedOffTheApproachAxis) {
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(50.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Eigen::Isometry3d block = Eigen::Isometry3d::Identity();
  block.linear() = tilt;
  block.translation() = Eigen::Vector3d(0.08, 0.0, 0.04);
  const TrueScene scene(boxMesh(kBlock), {block}, kBin);
  const Eigen::Vector3d normal = tilt.col(2);
  const Eigen::Vector3d approach = -normal;
  // The grasp frame's x towards vertical, seen along the approach: the bent body leans that way.
  const Eigen::Vector3d towards_up = (Eigen::Vector3d::UnitZ() + normal.z() * approach).normalized();
  Eigen::Isometry3d grasp = Eigen::Isometry3d::Identity();
  grasp.linear() << towards_up, approach.cross(towards_up), approach;
  grasp.translation() = block * Eigen::Vector3d(0.0, 0.0, 0.5 * kBlock.z());
  const double approach_distance = 0.03;
  const PickJudgement straight = judgePick(scene, grasp, suction(), approach_distance, PickTruthParams{});
  EXPECT_EQ(straight.reason, "tool hits the bin");
  picking::GripperParams bent = suction();
  bent.nose_angle_deg = 45.0;
  const PickJudgement upright = judgePick(scene, grasp, bent, approach_distance, PickTruthParams{});
  EXPECT_TRUE(upright.ok) << upright.reason;
}

TEST(SuctionTruth, BareFloorIsTheBin) {
  const TrueScene scene = boxes(kBlock, {});
  const PickJudgement j = judge(scene, fromAbove(0.0, 0.0, 0.0), suction());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "cup on the bin");
}

const Eigen::Vector3d kCube(0.040, 0.040, 0.040);

TEST(JawTruth, JawsCloseOnABoxNarrowerThanTheStroke) {
  const TrueScene scene = boxes(kCube, {{0.0, 0.0}});
  // The body's front 2 mm above the top, the finger tips 18 mm below it.
  const PickJudgement j = judge(scene, fromAbove(0.0, 0.0, 0.032), jaws());
  EXPECT_TRUE(j.ok) << j.reason;
  EXPECT_EQ(j.object, 0);
  EXPECT_NEAR(1e3 * j.distance, 40.0, 0.01);
  EXPECT_NEAR(j.angle_deg, 0.0, 0.01);
}

TEST(JawTruth, BoxWiderThanTheStrokeFails) {
  const TrueScene scene = boxes(Eigen::Vector3d(0.100, 0.040, 0.040), {{0.0, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.0, 0.0, 0.032), jaws());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "part wider than the stroke");
  EXPECT_EQ(j.touched, 0);
}

TEST(JawTruth, NeighbourWhereAFingerGoesFails) {
  // Part 1's near face at x = 44 mm, inside the open finger (x from 40 to 48 mm).
  const TrueScene scene = boxes(kCube, {{0.0, 0.0}, {0.064, 0.0}});
  const PickJudgement j = judge(scene, fromAbove(0.0, 0.0, 0.032), jaws());
  EXPECT_FALSE(j.ok);
  EXPECT_EQ(j.reason, "finger hits part 1");
  EXPECT_EQ(j.obstacle, 1);
  // Turned a quarter about the approach, the fingers close along y, clear of it.
  Eigen::Isometry3d turned = fromAbove(0.0, 0.0, 0.032);
  turned.linear() = turned.linear() * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(judge(scene, turned, jaws()).ok);
}

TEST(JawTruth, JawsOpenedToThePartsWidthPassBesideANeighbour) {
  // The 40 mm cube and a neighbour whose near face stands 44 mm off the axis, in the open finger's
  // way at the full 80 mm stroke but clear of jaws opened to 50 mm.
  const TrueScene scene = boxes(kCube, {{0.0, 0.0}, {0.064, 0.0}});
  const Eigen::Isometry3d above = fromAbove(0.0, 0.0, 0.032);
  EXPECT_FALSE(judgePick(scene, above, jaws(), kApproach, PickTruthParams{}).ok);
  const PickJudgement opened = judgePick(scene, above, jaws(), kApproach, PickTruthParams{}, 0.050);
  EXPECT_TRUE(opened.ok) << opened.reason;
  EXPECT_NEAR(1e3 * opened.distance, 40.0, 0.01);
  // Opened narrower than the part, the jaws land on it.
  const PickJudgement narrow = judgePick(scene, above, jaws(), kApproach, PickTruthParams{}, 0.030);
  EXPECT_FALSE(narrow.ok);
  EXPECT_EQ(narrow.reason, "part wider than the opening");
}

TEST(JawTruth, JawsOnTwoPartsOrNothingFail) {
  const TrueScene scene = boxes(Eigen::Vector3d(0.020, 0.040, 0.040), {{-0.015, 0.0}, {0.015, 0.0}});
  const PickJudgement two = judge(scene, fromAbove(0.0, 0.0, 0.032), jaws());
  EXPECT_FALSE(two.ok);
  EXPECT_EQ(two.reason, "jaws on two parts");
  const PickJudgement none = judge(scene, fromAbove(-0.120, 0.0, 0.032), jaws());
  EXPECT_FALSE(none.ok);
  EXPECT_EQ(none.reason, "nothing between the jaws");
}

TEST(PickTruth, RejectsBadInput) {
  const TrueScene scene = boxes(kBlock, {{0.0, 0.0}});
  PickTruthParams bad;
  bad.max_axis_angle_deg = 0.0;
  EXPECT_THROW(judgePick(scene, fromAbove(0, 0, 0.03), suction(), kApproach, bad), core::Error);
  try {
    bad = PickTruthParams{};
    bad.sample_spacing = 1.0;
    bad.validate();
    ADD_FAILURE() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("sample_spacing"), std::string::npos);
  }
  EXPECT_THROW(judgePick(scene, fromAbove(0, 0, 0.03), suction(), -1.0, PickTruthParams{}), core::Error);
  Eigen::Isometry3d scaled = fromAbove(0, 0, 0.03);
  scaled.linear() *= 2.0;
  EXPECT_THROW(judgePick(scene, scaled, suction(), kApproach, PickTruthParams{}), core::Error);
  EXPECT_THROW(TrueScene(io::TriangleMesh{}, {}, kBin), core::Error);
  EXPECT_THROW(TrueScene(boxMesh(kBlock), {}, simulation::BinInterior{0.4, 0.0, 0.1}), core::Error);
}

}  // namespace
}  // namespace binpick::emptying
