#pragma once
// Camera + projector calibration sequences from the virtual cell: a board (calibration_board.hpp)
// at random poses, each imaged under the full pattern set, written as capture directories with
// the truth beside them (docs/capture-format.md):
//   DIR/pose_000/ ...    one capture directory per pose (capture.json, images/), no calib.yaml
//   DIR/truth/rig.yaml   the true rig (writeRigCalibration)
//   DIR/truth/board.json the board spec, and per pose T_camera_board and every corner's true
//                        camera and projector pixel
// The board is alone in the scene, optionally in front of a dark wall so that the images are not
// black around it. Stateless functions: thread-safe for different directories.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/calibration_board.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "binpick/simulation/virtual_rig.hpp"

namespace binpick::simulation {

struct CalibrationSequenceParams {
  BoardSpec board;
  BoardPoseParams poses;  // count, seed and the working volume
  io::RigCalibration rig = makeVirtualRig();
  io::PatternSetSpec pattern_set;  // its projector size must be the rig projector's
  // Image formation, bit depth included. Its seed is ignored: renderCalibrationCapture takes the
  // noise seed as an argument, and writeCalibrationSequence derives one per pose from poses.seed.
  PhotometryParams photometry;
  SensorGeometryParams geometry;
  double texel_size = 1e-4;  // metres: the print's texture resolution (a quarter of the
                             // smallest camera pixel footprint at 0.7 m)
  // The print is averaged over each camera pixel's footprint on the board (a sensor pixel
  // integrates light over its area) from pixel_samples x pixel_samples points: edges and
  // corners come out anti-aliased, as in a real image.
  int pixel_samples = 5;
  double background_distance = 1.6;  // metres: camera z of a wall facing the camera; 0: none
  double background_albedo = 0.15;
  // Exposure at which `photometry` gives its counts, written to the metadata. Each pose shortens
  // it so that no board pixel of the white image exceeds max_white_counts (8-bit counts), as
  // one sets a real camera so that the board does not saturate; 0 keeps every pose at
  // exposure_us.
  double exposure_us = 8000.0;
  double max_white_counts = 235.0;
  std::string source = "binpick virtual cell: calibration sequence";
  void validate() const;  // throws core::Error naming the field, nested ones included
};

// One pose's capture: the images under every pattern of params.pattern_set, in pattern order,
// and the metadata (source, exposure, pattern names). `noise_seed` seeds the image noise.
io::Capture renderCalibrationCapture(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                                     const CalibrationSequenceParams& params, uint64_t noise_seed);
// The capture's first image, the white one, alone (the same pixels): for views that need no
// patterns.
cv::Mat renderCalibrationWhiteImage(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                                    const CalibrationSequenceParams& params, uint64_t noise_seed);

// Draws params.poses.count poses, renders and writes each as DIR/pose_NNN/, then writes
// DIR/truth/rig.yaml and DIR/truth/board.json last (a directory with truth/board.json holds a
// whole sequence). Returns the poses T_camera_board. Throws core::Error on bad params, when
// DIR exists and is not empty (never mixes two sequences), or when a file cannot be written.
std::vector<Eigen::Isometry3d> writeCalibrationSequence(const std::string& directory,
                                                        const CalibrationSequenceParams& params);

// DIR/truth/board.json read back.
struct CalibrationTruthPose {
  std::string capture;  // the pose's capture directory, relative to DIR ("pose_000")
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();
  std::vector<CornerObservation> corners;
};
struct CalibrationTruth {
  BoardSpec board;
  std::vector<BoardCorner> corners;  // the board's corners in the board frame
  std::vector<CalibrationTruthPose> poses;
};
// Throws core::Error "PATH: ..." on a missing file, malformed JSON, or a missing or mistyped
// key.
CalibrationTruth readCalibrationTruth(const std::string& directory);

}  // namespace binpick::simulation
