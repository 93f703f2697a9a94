// toolCollision against MeasuredScene (tool_collision.hpp): the suction cup and body, the swept
// approach, parallel fingers, the clearance; the scene built from an organized camera cloud.
// The gripper measured against: cup 16 mm wide, 25 mm long; body radius 25 mm, 150 mm long; the
// default sweep's margin, 2 mm.
#include <gtest/gtest.h>

#include <malloc.h>

#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "binpick/picking/tool_collision.hpp"
#include "measured_scene_support.hpp"
#include "picking_test_support.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

constexpr double kPlaneZ = 0.05;
constexpr double kMm = 0.001;

// Straight down onto (x, y, kPlaneZ), tilted by `tilt_deg` about base y: the tool's back end
// leans towards +x.
Eigen::Isometry3d graspAt(double x, double y, double tilt_deg = 0.0) {
  return pose({x, y, kPlaneZ}, rotY(tilt_deg) * rotX(180));
}

CloudBuilder flatPlane() {
  CloudBuilder cloud;
  cloud.slab(-0.1, 0.1, -0.1, 0.1, kPlaneZ);
  return cloud;
}

GripperParams measuredGripper() {
  GripperParams gripper;
  gripper.cup_diameter = 0.016;
  gripper.cup_length = 0.025;
  gripper.tool_radius = 0.025;
  gripper.tool_length = 0.15;
  return gripper;
}

ToolContact contact(const MeasuredScene& scene, const Eigen::Isometry3d& T_base_grasp,
                    const GripperParams& gripper = measuredGripper(), const ToolSweep& sweep = {}) {
  return toolCollision(scene, T_base_grasp, gripper, sweep);
}

TEST(PickingToolCollision, FlatPlaneUnderAVerticalSuctionGraspIsFree) {
  const MeasuredScene scene = flatPlane().scene();
  EXPECT_GT(scene.size(), 4000u);
  EXPECT_LT(scene.size(), 6000u);  // 1 mm samples thinned to 3 mm columns: 67 x 67
  const ToolContact free = contact(scene, graspAt(0, 0));
  EXPECT_FALSE(free.collision);
  // The plane under the cup is the seal; the body starts 25 mm up: the cap, 20 mm, is reached.
  EXPECT_NEAR(free.clearance, 0.02, 1e-9);
}

TEST(PickingToolCollision, APointAboveThePlaneCollidesOnlyInsideTheTool) {
  const MeasuredScene inside_cup = flatPlane().point(0.003, 0, kPlaneZ + 5 * kMm).scene();
  EXPECT_TRUE(contact(inside_cup, graspAt(0, 0)).collision);
  // Beside the cup (radius 10 mm with the margin), in front of the body (25 mm up): free.
  const MeasuredScene beside_cup = flatPlane().point(0.015, 0, kPlaneZ + 5 * kMm).scene();
  EXPECT_FALSE(contact(beside_cup, graspAt(0, 0)).collision);
  // Outside the tool's radius altogether, at any height.
  const MeasuredScene outside = flatPlane().column(0.04, 0, kPlaneZ, kPlaneZ + 0.2).scene();
  EXPECT_FALSE(contact(outside, graspAt(0, 0)).collision);
  // The same column under the body (radius 27 mm with the margin): hit.
  const MeasuredScene under_body = flatPlane().column(0.025, 0, kPlaneZ, kPlaneZ + 0.2).scene();
  EXPECT_TRUE(contact(under_body, graspAt(0, 0)).collision);
}

TEST(PickingToolCollision, TheApproachSweepsTheBodyBackToThePreGrasp) {
  // A point 230 mm above the grasp on the axis: beyond the body (25 + 150 mm + margin) but within
  // its sweep from the pre-grasp point, 100 mm further back.
  const MeasuredScene scene = flatPlane().point(0, 0, kPlaneZ + 0.23).scene();
  EXPECT_TRUE(contact(scene, graspAt(0, 0)).collision);
  ToolSweep no_approach;
  no_approach.approach_distance = 0.0;
  EXPECT_FALSE(contact(scene, graspAt(0, 0), measuredGripper(), no_approach).collision);
}

// A neighbour's column 60 mm to the side: a vertical tool stays 33 mm from it, one tilted 30
// degrees towards it reaches it with its body (its axis is 58 mm over at 100 mm up). No plane
// here: a cup tilted against a plane would itself dig into it.
TEST(PickingToolCollision, ANeighbourColumnBesideATiltedApproachHitsTheBody) {
  const MeasuredScene scene = CloudBuilder().column(0.06, 0, kPlaneZ, kPlaneZ + 0.12).scene();
  EXPECT_FALSE(contact(scene, graspAt(0, 0)).collision);
  EXPECT_TRUE(contact(scene, graspAt(0, 0, 30)).collision);
  EXPECT_FALSE(contact(scene, graspAt(0, 0, -30)).collision);  // leaning away
}

// A 30-degree bent nose on a vertical approach: the body leans towards base +x (the grasp frame's
// +x here), its axis 0.5 m over per metre along it. A column 60 mm off the axis on that side,
// free for the straight tool, meets the body 120 mm along it; a point on the approach axis 230 mm
// up, in the straight body's sweep, lies 52 mm off the bent one's axis even at the pre-grasp point.
TEST(PickingToolCollision, ABentNosesBodyLeavesTheApproachAxis) {
  GripperParams bent = measuredGripper();
  bent.nose_angle_deg = 30.0;
  const MeasuredScene column = CloudBuilder().column(0.06, 0, kPlaneZ, kPlaneZ + 0.2).scene();
  EXPECT_FALSE(contact(column, graspAt(0, 0)).collision);
  EXPECT_TRUE(contact(column, graspAt(0, 0), bent).collision);
  const MeasuredScene mirrored = CloudBuilder().column(-0.06, 0, kPlaneZ, kPlaneZ + 0.2).scene();
  EXPECT_FALSE(contact(mirrored, graspAt(0, 0), bent).collision);
  const MeasuredScene above = flatPlane().point(0, 0, kPlaneZ + 0.23).scene();
  EXPECT_TRUE(contact(above, graspAt(0, 0)).collision);
  EXPECT_FALSE(contact(above, graspAt(0, 0), bent).collision);
}

// The bent body's clearance is its true distance, over the whole sweep: a point 10 mm out along
// -x from the lower rim on the side the body leans away from (r = 27 mm with the margin, the
// body's start pulled a margin towards the cup) lies outside both the rim's side and its end, so
// the rim itself is nearest; moving the body back along the approach only takes it further away.
TEST(PickingToolCollision, ABentNosesClearanceIsTheDistanceToItsRim) {
  GripperParams bent = measuredGripper();
  bent.nose_angle_deg = 30.0;
  const double r = 0.027, margin = 0.002;
  const Eigen::Vector3d axis(0.5, 0.0, std::sqrt(3.0) / 2.0);  // base frame
  const Eigen::Vector3d start = Eigen::Vector3d(0, 0, kPlaneZ + 0.025) - margin * axis;
  const Eigen::Vector3d rim = start + r * Eigen::Vector3d(-axis.z(), 0.0, axis.x());
  const Eigen::Vector3d point(rim.x() - 0.01, 0.0, rim.z());
  const MeasuredScene scene = CloudBuilder().point(point.x(), point.y(), point.z()).scene();
  const ToolContact free = contact(scene, graspAt(0, 0), bent);
  ASSERT_FALSE(free.collision);
  EXPECT_NEAR(free.clearance / kMm, 10.0, 0.01);
}

TEST(PickingToolCollision, ClearanceGrowsWithTheNeighboursDistance) {
  double previous = -1.0;
  for (const double distance_mm : {30.0, 35.0, 40.0, 45.0}) {
    const MeasuredScene scene = flatPlane().column(distance_mm * kMm, 0, kPlaneZ, kPlaneZ + 0.2).scene();
    const ToolContact free = contact(scene, graspAt(0, 0));
    ASSERT_FALSE(free.collision) << distance_mm << " mm";
    // The body's radius with the margin is 27 mm.
    EXPECT_NEAR(free.clearance / kMm, distance_mm - 27.0, 0.01) << distance_mm << " mm";
    EXPECT_GT(free.clearance, previous);
    previous = free.clearance;
  }
  const MeasuredScene far = flatPlane().column(0.06, 0, kPlaneZ, kPlaneZ + 0.2).scene();
  EXPECT_NEAR(contact(far, graspAt(0, 0)).clearance, 0.02, 1e-9);  // capped
}

// A 30 mm wide block with its top 10 mm above the grasp point, on a floor 30 mm below it; the
// fingers (30 mm deep, 8 mm thick) open to 30 + 2 x 5 mm.
class PickingParallelFingers : public ::testing::Test {
 protected:
  PickingParallelFingers() {
    gripper = measuredGripper();
    gripper.type = GripperType::Parallel;
    gripper.finger_depth = 0.03;
    sweep.opening = 0.04;
    block.slab(-0.1, 0.1, -0.1, 0.1, kPlaneZ - 0.03);          // floor
    block.slab(-0.015, 0.015, -0.015, 0.015, kPlaneZ + 0.01);  // top
    for (const double x : {-0.015, 0.015}) {                   // sides
      for (double y = -0.015; y <= 0.015; y += kSampleStep) block.column(x, y, kPlaneZ - 0.03, kPlaneZ + 0.01);
    }
  }
  GripperParams gripper;
  ToolSweep sweep;
  CloudBuilder block;
};

TEST_F(PickingParallelFingers, TheBlockAloneIsFree) {
  const ToolContact free = contact(block.scene(), graspAt(0, 0), gripper, sweep);
  EXPECT_FALSE(free.collision);
  // The part between the jaws does not count; the body's front, 5 mm above the block's top
  // (minus the margin), does.
  EXPECT_NEAR(free.clearance / kMm, 3.0, 0.01);
}

TEST_F(PickingParallelFingers, ANeighbourBesideTheBlockHitsAFinger) {
  CloudBuilder crowded = block;
  crowded.slab(0.022, 0.05, -0.02, 0.02, kPlaneZ + 0.005);  // within the finger's 18..30 mm
  EXPECT_TRUE(contact(crowded.scene(), graspAt(0, 0), gripper, sweep).collision);
  // Turned a quarter about the approach, the fingers close along y and miss it.
  const Eigen::Isometry3d turned = graspAt(0, 0) * pose({0, 0, 0}, rotZ(90));
  EXPECT_FALSE(contact(crowded.scene(), turned, gripper, sweep).collision);
  // An unknown width opens the jaws to the full 80 mm stroke: the finger lands beyond it.
  CloudBuilder far = block;
  far.slab(0.022, 0.034, -0.02, 0.02, kPlaneZ + 0.005);
  EXPECT_TRUE(contact(far.scene(), graspAt(0, 0), gripper, sweep).collision);
  ToolSweep wide = sweep;
  wide.opening = 0.0;
  EXPECT_FALSE(contact(far.scene(), graspAt(0, 0), gripper, wide).collision);
}

// A 1280 x 1024 camera 1 m above a floor with a 40 mm bump, looking down; every 7th row lost.
io::PointCloud cameraCloud(const Eigen::Isometry3d& T_base_camera) {
  io::PointCloud cloud;
  cloud.width = 1280;
  cloud.height = 1024;
  const Eigen::Isometry3d T_camera_base = T_base_camera.inverse();
  const double pitch = 0.0005;  // metres per pixel on the floor
  for (int row = 0; row < cloud.height; ++row) {
    for (int column = 0; column < cloud.width; ++column) {
      if (row % 7 == 3) {
        cloud.points.emplace_back(Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
        continue;
      }
      const double x = (column - 640) * pitch, y = (row - 512) * pitch;
      const bool on_bump = std::abs(x - 0.1) < 0.02 && std::abs(y) < 0.02;
      cloud.points.emplace_back((T_camera_base * Eigen::Vector3d(x, y, on_bump ? 0.04 : 0.0)).cast<float>());
    }
  }
  return cloud;
}

TEST(PickingToolCollision, SceneFromAnOrganizedCameraCloudIsInTheBaseFrameAndThinned) {
  const Eigen::Isometry3d T_base_camera = pose({0.01, -0.02, 1.0}, rotZ(20) * rotX(180));
  const MeasuredScene scene(cameraCloud(T_base_camera), T_base_camera);
  // 640 x 512 mm at 3 mm steps: about 36 000 columns, one point each (two at the bump's edge).
  EXPECT_GT(scene.size(), 30000u);
  EXPECT_LT(scene.size(), 45000u);
  for (const Eigen::Vector3f& p : scene.points()) {
    ASSERT_TRUE(std::abs(p.z()) < 1e-4 || std::abs(p.z() - 0.04) < 1e-4) << p.transpose();
  }
  const Eigen::Isometry3d on_floor = pose({-0.1, 0, 0}, rotX(180));
  EXPECT_FALSE(toolCollision(scene, on_floor, measuredGripper(), {}).collision);
  const Eigen::Isometry3d beside_bump = pose({0.1 - 0.035, 0, 0}, rotX(180));
  EXPECT_TRUE(toolCollision(scene, beside_bump, measuredGripper(), {}).collision);  // the bump under the body
  EXPECT_NEAR(scene.shareCoveredAbove({0.1, 0, 0}, 0.01, 0.005), 1.0, 1e-9);
  EXPECT_NEAR(scene.shareCoveredAbove({-0.1, 0, 0}, 0.04, 0.005), 0.0, 1e-9);
}

// Bytes the heap holds now; 0 where glibc's count is not there (a sanitizer's allocator).
long long heapBytes() {
#if defined(__GLIBC__)
  return static_cast<long long>(mallinfo2().uordblks);
#else
  return 0;
#endif
}

constexpr long long kMaxSceneBytes = 8 << 20;  // a 200 x 200 mm plane's scene takes about 0.1 MB

// One stray point far out (a mismatched stripe, a reflection) is left out: it neither stretches
// the grid (memory, the column count's int) nor coarsens it (the tool's view of the plane).
TEST(PickingToolCollision, AFarOutlierIsLeftOutAndTheGridStaysBounded) {
  const auto plane = [] { return flatPlane().column(0.03, 0, kPlaneZ, kPlaneZ + 0.2); };
  const MeasuredScene reference = plane().scene();
  const ToolContact reference_contact = contact(reference, graspAt(0, 0));
  ASSERT_FALSE(reference_contact.collision);
  const float huge = std::numeric_limits<float>::max();
  for (const Eigen::Vector2d& far : {Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(1e9, 0.0), Eigen::Vector2d(huge, 0.0),
                                     Eigen::Vector2d(-1e12, 1e12), Eigen::Vector2d(0.0, -huge)}) {
    const CloudBuilder cloud = plane().point(far.x(), far.y(), kPlaneZ);
    const long long before = heapBytes();
    const MeasuredScene scene = cloud.scene();
    EXPECT_LT(heapBytes() - before, kMaxSceneBytes) << far.transpose();
    EXPECT_EQ(scene.size(), reference.size()) << far.transpose();
    const ToolContact with_outlier = contact(scene, graspAt(0, 0));
    EXPECT_EQ(with_outlier.collision, reference_contact.collision) << far.transpose();
    EXPECT_EQ(with_outlier.clearance, reference_contact.clearance) << far.transpose();
    EXPECT_TRUE(contact(scene, graspAt(0.026, 0)).collision) << far.transpose();  // the column
    EXPECT_EQ(scene.shareCoveredAbove({0.03, 0, kPlaneZ}, 0.01, 0.005),
              reference.shareCoveredAbove({0.03, 0, kPlaneZ}, 0.01, 0.005));
  }
  // A camera point within the float range that leaves it in the base frame.
  const Eigen::Isometry3d T_base_camera = pose(Eigen::Vector3d::Zero(), rotZ(45));
  io::PointCloud camera_cloud;
  for (const Eigen::Vector3f& p : plane().points)
    camera_cloud.points.push_back((T_base_camera.inverse() * p.cast<double>()).cast<float>());
  camera_cloud.points.emplace_back(huge, huge, 0.0f);
  const MeasuredScene turned(camera_cloud, T_base_camera);
  EXPECT_EQ(turned.size(), reference.size());
  EXPECT_TRUE(contact(turned, graspAt(0.026, 0)).collision);
  // Within a metre of the cloud a point is no outlier: the tool may meet it.
  const MeasuredScene near = plane().point(0.5, 0, kPlaneZ).scene();
  EXPECT_EQ(near.size(), reference.size() + 1);
}

// A cloud that is all spread, a thousand points a thousand kilometres apart on a line with no
// width: no bulk to keep, so the columns grow instead, bounded along the line as across it, and a
// query still finds what lies in the tool.
TEST(PickingToolCollision, ACloudSpreadOverKilometresStaysBounded) {
  CloudBuilder cloud;
  for (int i = 0; i <= 1000; ++i) cloud.point(i * 1e6, 0.0, 0.0);
  cloud.point(0.003, 0, kPlaneZ + 0.005);  // in the cup of a grasp at the origin
  const long long before = heapBytes();
  const MeasuredScene scene = cloud.scene();
  EXPECT_LT(heapBytes() - before, kMaxSceneBytes);
  EXPECT_EQ(scene.size(), cloud.points.size());
  EXPECT_TRUE(contact(scene, graspAt(0, 0)).collision);
  EXPECT_FALSE(contact(scene, graspAt(0, 0.5)).collision);
}

TEST(PickingToolCollision, AnEmptySceneHoldsNothingAndBadInputThrows) {
  const MeasuredScene empty(io::PointCloud{}, Eigen::Isometry3d::Identity());
  EXPECT_EQ(empty.size(), 0u);
  const ToolContact free = toolCollision(empty, graspAt(0, 0), measuredGripper(), {});
  EXPECT_FALSE(free.collision);
  EXPECT_NEAR(free.clearance, 0.02, 1e-12);
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  EXPECT_THROW(MeasuredScene(io::PointCloud{}, scaled), core::Error);
  MeasuredSceneParams params;
  params.thin_step = 0.0;
  EXPECT_THROW(MeasuredScene(io::PointCloud{}, Eigen::Isometry3d::Identity(), params), core::Error);
}

}  // namespace
}  // namespace binpick::picking
