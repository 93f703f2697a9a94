#pragma once
// Hand-eye sessions in the virtual cell: a robot that moves the board in front of a fixed camera
// (eye-to-hand) or the camera over a fixed board (eye-in-hand), with the robot poses it reports
// and the camera images, written as a hand-eye views directory (docs/hand-eye.md):
//   DIR/poses.txt            the robot poses T_base_flange with noise, in params.orientation
//   DIR/view_NN.png          each view's camera image (the board under the projector's white)
//   DIR/calib.yaml           the rig, for the camera intrinsics
//   DIR/truth/hand_eye.yaml  the true transforms, in the result file format (hand_eye_file.hpp)
// Board poses come from randomBoardPoses (the whole board in view) and the robot poses follow
// from them and the true transforms, so every view is one the camera can take.
// Stateless functions: thread-safe for different directories.
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/calibration/hand_eye.hpp"
#include "binpick/core/orientation.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/calibration_board.hpp"
#include "binpick/simulation/virtual_rig.hpp"

namespace binpick::simulation {

// The virtual cell's truth for each setup (docs/virtual-cell.md): the camera 0.9 m above the
// bin looking down (config/demo-binpickd.yaml), the board 30 mm out from the flange, turned and
// off-centre; the camera 90 mm out from the flange, the board on the table.
Eigen::Isometry3d virtualCellBaseCamera();
Eigen::Isometry3d virtualCellFlangeBoard(const BoardSpec& board);
Eigen::Isometry3d virtualCellFlangeCamera();
Eigen::Isometry3d virtualCellBaseBoard(const BoardSpec& board);

struct HandEyeSessionParams {
  calibration::HandEyeSetup setup = calibration::HandEyeSetup::EyeToHand;
  int views = 12;
  uint64_t seed = 1;  // board poses, robot noise and image noise
  // Noise of the reported robot poses, per axis: the flange position (mm, base frame) and a
  // rotation vector about the flange's axes (degrees). Real arms: ~0.1 mm, ~0.05 deg.
  double robot_noise_mm = 0.0;
  double robot_noise_deg = 0.0;
  core::Orientation orientation = core::Orientation::EulerZYX;  // of poses.txt
  BoardSpec board;
  io::RigCalibration rig = makeVirtualRig();
  BoardPoseParams poses;  // the working volume; count and seed come from views and seed
  // The truth: T_base_camera and T_flange_board (eye-to-hand), T_flange_camera and
  // T_base_board (eye-in-hand); the other setup's pair is unused.
  Eigen::Isometry3d T_base_camera = virtualCellBaseCamera();
  Eigen::Isometry3d T_flange_board = virtualCellFlangeBoard(BoardSpec{});
  Eigen::Isometry3d T_flange_camera = virtualCellFlangeCamera();
  Eigen::Isometry3d T_base_board = virtualCellBaseBoard(BoardSpec{});
  void validate() const;  // throws core::Error naming the field
};

struct HandEyeSessionView {
  std::string name;  // "view_00", ...
  Eigen::Isometry3d T_base_flange_true = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity();   // reported, with noise
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  // true
};

struct HandEyeSession {
  calibration::HandEyeSetup setup = calibration::HandEyeSetup::EyeToHand;
  Eigen::Isometry3d T_mount_camera = Eigen::Isometry3d::Identity();  // the truth
  Eigen::Isometry3d T_mount_board = Eigen::Isometry3d::Identity();
  std::vector<HandEyeSessionView> views;
};

// The poses only, no images: for solver tests and benchmarks. Throws core::Error on bad
// params.
HandEyeSession simulateHandEyeSession(const HandEyeSessionParams& params);

// The camera image of the board at T_camera_board: the white image of a calibration capture
// (calibration_sequence.hpp) rendered with the fewest patterns, 8-bit, noise from `noise_seed`.
cv::Mat renderHandEyeImage(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                           const HandEyeSessionParams& params, uint64_t noise_seed);

// Simulates, renders and writes the views directory and its truth; returns the session. Throws
// core::Error on bad params, when DIR exists and is not empty, or when a file cannot be
// written.
HandEyeSession writeHandEyeSession(const std::string& directory, const HandEyeSessionParams& params);

}  // namespace binpick::simulation
