// Simulated hand-eye sessions: robot poses consistent with the truth, seeded noise of the asked
// size, images in which the board is where the truth puts it, and the views directory on disk.
#include "binpick/simulation/hand_eye_session.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/calibration/hand_eye_file.hpp"
#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/io/image_file.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::simulation {
namespace {

using calibration::HandEyeSetup;
using calibration::poseDifference;

HandEyeSessionParams paramsFor(HandEyeSetup setup, int views = 12) {
  HandEyeSessionParams params;
  params.setup = setup;
  params.views = views;
  return params;
}

// The board in the mount frame by the robot's way and by the camera's way agree exactly.
TEST(HandEyeSession, TrueRobotPosesPutTheBoardWhereTheCameraSeesIt) {
  for (const HandEyeSetup setup : {HandEyeSetup::EyeToHand, HandEyeSetup::EyeInHand}) {
    const HandEyeSession s = simulateHandEyeSession(paramsFor(setup));
    ASSERT_EQ(s.views.size(), 12u);
    EXPECT_EQ(s.views[11].name, "view_11");
    for (const HandEyeSessionView& v : s.views) {
      const Eigen::Isometry3d base_board = setup == HandEyeSetup::EyeToHand
                                               ? s.T_mount_camera * v.T_camera_board
                                               : v.T_base_flange_true * s.T_mount_camera * v.T_camera_board;
      const Eigen::Isometry3d expected =
          setup == HandEyeSetup::EyeToHand ? v.T_base_flange_true * s.T_mount_board : s.T_mount_board;
      EXPECT_LT(poseDifference(base_board, expected).translation_mm, 1e-9);
      EXPECT_LT(poseDifference(v.T_base_flange, v.T_base_flange_true).translation_mm, 1e-12);
    }
  }
}

TEST(HandEyeSession, RobotNoiseHasTheAskedSizeAndSeed) {
  HandEyeSessionParams params = paramsFor(HandEyeSetup::EyeToHand, 100);
  params.robot_noise_mm = 0.5;
  params.robot_noise_deg = 0.2;
  const HandEyeSession s = simulateHandEyeSession(params);
  double mm2 = 0.0, deg2 = 0.0;
  for (const HandEyeSessionView& v : s.views) {
    const calibration::PoseDifference d = poseDifference(v.T_base_flange, v.T_base_flange_true);
    mm2 += d.translation_mm * d.translation_mm;
    deg2 += d.rotation_deg * d.rotation_deg;
  }
  // Per-axis sigma s: the RMS length of the 3-vector is sqrt(3) s.
  EXPECT_NEAR(std::sqrt(mm2 / 100.0), std::sqrt(3.0) * 0.5, 0.1);
  EXPECT_NEAR(std::sqrt(deg2 / 100.0), std::sqrt(3.0) * 0.2, 0.04);
  const HandEyeSession again = simulateHandEyeSession(params);
  EXPECT_TRUE(again.views[17].T_base_flange.isApprox(s.views[17].T_base_flange, 0.0));
  params.seed = 2;
  EXPECT_FALSE(simulateHandEyeSession(params).views[17].T_base_flange.isApprox(s.views[17].T_base_flange, 1e-6));
}

// The rendered image holds the whole board, and its pose from the image is the truth's.
TEST(HandEyeSession, TheImageShowsTheBoardAtItsTruePose) {
  const HandEyeSessionParams params = paramsFor(HandEyeSetup::EyeInHand, 1);
  const HandEyeSession s = simulateHandEyeSession(params);
  const CalibrationBoard board(params.board);
  const cv::Mat image = renderHandEyeImage(board, s.views[0].T_camera_board, params, 5);
  ASSERT_EQ(image.type(), CV_8UC1);
  const calibration::BoardLayout layout = params.board.layout();
  const calibration::BoardDetection detection = calibration::detectBoard(image, layout);
  ASSERT_TRUE(detection.complete()) << detection.problem;
  const auto pose = calibration::estimateBoardPose(detection, layout, params.rig.camera);
  ASSERT_TRUE(pose.has_value());
  const calibration::PoseDifference d = poseDifference(pose->T_camera_board, s.views[0].T_camera_board);
  EXPECT_LT(d.translation_mm, 2.0);
  EXPECT_LT(d.rotation_deg, 0.2);
  EXPECT_LT(pose->rms_px, 0.3);
}

class HandEyeSessionFiles : public test::TempDirectoryTest {};

// A quarter-resolution camera renders sixteen times faster; the files are what is checked.
TEST_F(HandEyeSessionFiles, WritesTheViewsDirectoryAndTheTruth) {
  HandEyeSessionParams params = paramsFor(HandEyeSetup::EyeToHand, 2);
  io::LensIntrinsics& camera = params.rig.camera;
  camera = camera.scaled(0.25);
  params.robot_noise_mm = 0.1;
  params.orientation = core::Orientation::Quaternion;
  const std::string dir = pathOf("session");
  const HandEyeSession s = writeHandEyeSession(dir, params);
  for (const char* file : {"view_00.png", "view_01.png", "calib.yaml", "truth/hand_eye.yaml"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  EXPECT_EQ(io::readImageFile(dir + "/view_01.png").cols, camera.width);
  const calibration::RobotPoseFile poses = calibration::readRobotPoseFile(dir + "/poses.txt");
  EXPECT_EQ(poses.orientation, core::Orientation::Quaternion);
  ASSERT_EQ(poses.poses.size(), 2u);
  EXPECT_LT(poseDifference(poses.poses[1].T_base_flange, s.views[1].T_base_flange).translation_mm, 1e-3);
  const calibration::HandEyeFile truth = calibration::readHandEyeFile(dir + "/truth/hand_eye.yaml");
  EXPECT_EQ(truth.setup, HandEyeSetup::EyeToHand);
  EXPECT_EQ(truth.method, "truth");
  EXPECT_LT(poseDifference(truth.T_mount_camera, virtualCellBaseCamera()).translation_mm, 1e-6);
  EXPECT_LT(poseDifference(truth.T_mount_board, s.T_mount_board).rotation_deg, 1e-6);
  EXPECT_TRUE(test::throwsNaming([&] { writeHandEyeSession(dir, params); }, "not empty"));
}

TEST(HandEyeSession, BadParamsNameTheField) {
  HandEyeSessionParams noisy;
  noisy.robot_noise_deg = -1.0;
  EXPECT_TRUE(test::throwsNaming([&] { simulateHandEyeSession(noisy); }, "HandEyeSessionParams.robot_noise_deg"));
  HandEyeSessionParams scaled;
  scaled.T_flange_board.linear() *= 2.0;
  EXPECT_TRUE(test::throwsNaming([&] { simulateHandEyeSession(scaled); }, "HandEyeSessionParams.T_flange_board"));
}

}  // namespace
}  // namespace binpick::simulation
