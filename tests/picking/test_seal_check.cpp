// The seal test on a measured surface: a camera looking straight down at a 20 mm square plateau
// standing 10 mm proud of a floor, 0.5 mm pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "binpick/picking/seal_check.hpp"
#include "picking_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::picking {
namespace {

using namespace binpick::picking::test;

constexpr double kFloorZ = 0.50, kPlateauZ = 0.49, kHalfPlateau = 0.010;  // camera frame, metres

io::LensIntrinsics downwardCamera() {
  io::LensIntrinsics camera;
  camera.width = 200;
  camera.height = 160;
  camera.fx = camera.fy = 1000.0;  // 0.5 mm per pixel at 0.5 m
  camera.cx = 99.5;
  camera.cy = 79.5;
  return camera;
}

// Each pixel's ray meets the plateau's top or the floor; `hole` pixels measured nothing.
io::PointCloud plateauCloud(const io::LensIntrinsics& camera, bool (*hole)(double x, double y) = nullptr) {
  io::PointCloud cloud;
  cloud.width = camera.width;
  cloud.height = camera.height;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      Eigen::Vector3d point = ray * kPlateauZ;
      if (std::abs(point.x()) > kHalfPlateau || std::abs(point.y()) > kHalfPlateau) point = ray * kFloorZ;
      const bool lost = hole && hole(point.x(), point.y());
      const float nan = std::numeric_limits<float>::quiet_NaN();
      cloud.points.push_back(lost ? Eigen::Vector3f(nan, nan, nan) : point.cast<float>());
    }
  }
  return cloud;
}

// A cup of 6 mm at (x, y) on the plateau's height, approaching along the camera's z (straight down).
SealCheck checkAt(const MeasuredSurface& surface, double x, double y, double z = kPlateauZ) {
  return surface.check(pose({x, y, z}), 0.003, 0.0008, SealCheckParams{});
}

TEST(PickingSeal, ACupInsideTheFaceSeals) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  const MeasuredSurface surface(cloud, camera, Eigen::Isometry3d::Identity());
  const SealCheck centred = checkAt(surface, 0.0, 0.0);
  EXPECT_TRUE(centred.seals);
  EXPECT_DOUBLE_EQ(centred.seen_share, 1.0);
  EXPECT_LT(centred.worst_deviation, 1e-6);
  EXPECT_TRUE(checkAt(surface, 0.006, -0.006).seals);  // 0.5 mm rim margin still on the face
}

TEST(PickingSeal, ACupOverTheEdgeOrAtTheWrongHeightDoesNot) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  const MeasuredSurface surface(cloud, camera, Eigen::Isometry3d::Identity());
  const SealCheck over_edge = checkAt(surface, 0.0085, 0.0);  // the disc reaches 1.5 mm past the edge
  EXPECT_FALSE(over_edge.seals);
  EXPECT_NEAR(over_edge.worst_deviation, kFloorZ - kPlateauZ, 1e-4);
  EXPECT_FALSE(checkAt(surface, 0.0, 0.0, kPlateauZ - 0.003).seals);  // 3 mm above the face: no part there
  EXPECT_TRUE(checkAt(surface, 0.0, 0.0, kPlateauZ - 0.0008).seals);  // within tolerance + noise
}

TEST(PickingSeal, ATiltedCupMeasuresTheFaceAgainstItsOwnPlane) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  const MeasuredSurface surface(cloud, camera, Eigen::Isometry3d::Identity());
  // 30 degrees off the face's normal: the disc's rim lies 1.5 mm off the face.
  EXPECT_FALSE(surface.check(pose({0, 0, kPlateauZ}, rotX(30)), 0.003, 0.0008, SealCheckParams{}).seals);
  EXPECT_TRUE(surface.check(pose({0, 0, kPlateauZ}, rotX(5)), 0.003, 0.0008, SealCheckParams{}).seals);
}

// 11 degrees off the face: its rim only 0.68 mm off the face, inside the depth tolerance, but the
// plane the samples measure is turned beyond max_angle_deg (8).
TEST(PickingSeal, ACupTurnedOffTheMeasuredSurfaceDoesNotSeal) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  const MeasuredSurface surface(cloud, camera, Eigen::Isometry3d::Identity());
  const SealCheck turned = surface.check(pose({0, 0, kPlateauZ}, rotY(11)), 0.003, 0.0008, SealCheckParams{});
  EXPECT_FALSE(turned.seals);
  EXPECT_NEAR(turned.angle_deg, 11.0, 0.1);
  EXPECT_LT(turned.worst_deviation, 0.0008);
  SealCheckParams lenient;
  lenient.max_angle_deg = 12.0;
  EXPECT_TRUE(surface.check(pose({0, 0, kPlateauZ}, rotY(11)), 0.003, 0.0008, lenient).seals);
}

TEST(PickingSeal, UnmeasuredPixelsUnderTheCupFailIt) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud shadowed = plateauCloud(camera, [](double x, double) { return x > 0.001; });
  const MeasuredSurface surface(shadowed, camera, Eigen::Isometry3d::Identity());
  const SealCheck half_seen = checkAt(surface, 0.0, 0.0);
  EXPECT_FALSE(half_seen.seals);
  EXPECT_LT(half_seen.seen_share, 0.8);
  EXPECT_TRUE(checkAt(surface, -0.005, 0.0).seals);  // wholly on the measured side
}

TEST(PickingSeal, AnUnmeasuredRimNextToTheFarSideOfAnEdgeFails) {
  const io::LensIntrinsics camera = downwardCamera();
  // A band along the plateau's +x edge measured nothing (a shadow): a few of the 49 samples fall
  // in it, fewer than the share allowed unseen here, but the floor measured beside them shows
  // the edge.
  const io::PointCloud shadowed = plateauCloud(camera, [](double x, double) { return x > 0.0093 && x < 0.0105; });
  const MeasuredSurface surface(shadowed, camera, Eigen::Isometry3d::Identity());
  SealCheckParams params;
  params.min_seen_share = 0.8;
  const SealCheck at_edge = surface.check(pose({0.0062, 0.0, kPlateauZ}), 0.003, 0.0008, params);
  EXPECT_GT(at_edge.seen_share, params.min_seen_share);
  EXPECT_LT(at_edge.seen_share, 1.0);
  EXPECT_FALSE(at_edge.seals);
  EXPECT_TRUE(surface.check(pose({0.0030, 0.0, kPlateauZ}), 0.003, 0.0008, params).seals);
}

TEST(PickingSeal, ACupJustOverTheEdgeSlidesBackOntoTheFace) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  const MeasuredSurface surface(cloud, camera, Eigen::Isometry3d::Identity());
  const SealCheckParams params;                                        // up to 2 mm in 1 mm steps
  const Eigen::Isometry3d over_edge = pose({0.0075, 0.0, kPlateauZ});  // 1 mm too far out
  ASSERT_FALSE(checkAt(surface, 0.0075, 0.0).seals);
  const auto slid = surface.findSeal(over_edge, 0.003, 0.0008, params);
  ASSERT_TRUE(slid.has_value());
  const Eigen::Vector3d moved = slid->translation() - over_edge.translation();
  EXPECT_LE(1e3 * moved.norm(), 2.0 + 1e-9);
  EXPECT_LT(slid->translation().x(), over_edge.translation().x());  // back towards the face
  EXPECT_NEAR(moved.z(), 0.0, 1e-12);                               // along the face only
  EXPECT_TRUE(surface.check(*slid, 0.003, 0.0008, params).seals);
  // 3 mm out is further than it may slide; a cup that seals where it is stays there.
  EXPECT_FALSE(surface.findSeal(pose({0.0095, 0.0, kPlateauZ}), 0.003, 0.0008, params).has_value());
  const Eigen::Isometry3d centred = pose({0.0, 0.0, kPlateauZ});
  EXPECT_TRUE(surface.findSeal(centred, 0.003, 0.0008, params)->isApprox(centred));
}

TEST(PickingSeal, TheBaseFrameIsHonoured) {
  const io::LensIntrinsics camera = downwardCamera();
  const io::PointCloud cloud = plateauCloud(camera);
  // The camera 0.9 m above the base origin looking down: base z up is camera -z.
  const Eigen::Isometry3d T_base_camera = pose({0.3, 0.0, 0.9}, rotX(180));
  const MeasuredSurface surface(cloud, camera, T_base_camera);
  const Eigen::Isometry3d on_plateau = T_base_camera * pose({0.002, -0.001, kPlateauZ});
  EXPECT_TRUE(surface.check(on_plateau, 0.003, 0.0008, SealCheckParams{}).seals);
  const Eigen::Isometry3d on_floor_edge = T_base_camera * pose({0.0095, 0.0, kPlateauZ});
  EXPECT_FALSE(surface.check(on_floor_edge, 0.003, 0.0008, SealCheckParams{}).seals);
}

TEST(PickingSeal, AnAngleLimitOutsideItsRangeThrowsNamingIt) {
  SealCheckParams params;
  params.max_angle_deg = 0.0;
  EXPECT_TRUE(binpick::test::throwsNaming([&] { params.validate(); }, "max_angle_deg"));
  params.max_angle_deg = 91.0;
  EXPECT_TRUE(binpick::test::throwsNaming([&] { params.validate(); }, "max_angle_deg"));
}

TEST(PickingSeal, RejectsACloudNotOrganizedAsTheCamera) {
  const io::LensIntrinsics camera = downwardCamera();
  io::PointCloud cloud = plateauCloud(camera);
  cloud.width = 100;
  EXPECT_THROW(MeasuredSurface(cloud, camera, Eigen::Isometry3d::Identity()), core::Error);
  SealCheckParams params;
  params.min_seen_share = 1.5;
  EXPECT_THROW(params.validate(), core::Error);
}

}  // namespace
}  // namespace binpick::picking
