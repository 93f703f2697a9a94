// writeCalibrationSequence: poses, one capture directory each, then the truth.
#include "binpick/simulation/calibration_sequence.hpp"

#include <cstdio>
#include <filesystem>

#include "binpick/io/error.hpp"
#include "calibration_truth.hpp"
#include "random.hpp"

namespace binpick::sim {
namespace {

namespace fs = std::filesystem;

// Own random stream under the pose seed: one image-noise seed per pose, in pose order.
constexpr uint32_t kPoseNoiseStream = 11;

std::string poseDirectoryName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "pose_%03d", index);
  return name;
}

// Never mix two sequences: the caller picks a new (or empty) directory.
void requireFreshDirectory(const std::string& directory) {
  std::error_code error;
  if (fs::exists(directory, error) && !fs::is_empty(directory, error)) {
    throw Error(directory +
                ": already exists and is not empty; write each calibration sequence"
                " to a new directory");
  }
}

}  // namespace

std::vector<Eigen::Isometry3d> writeCalibrationSequence(const std::string& directory,
                                                        const CalibrationSequenceParams& params) {
  params.validate();
  requireFreshDirectory(directory);
  const CalibrationBoard board(params.board, params.texel_size);
  const std::vector<Eigen::Isometry3d> poses = randomBoardPoses(board, params.rig, params.poses);
  detail::Rng noise_seeds = detail::makeRng(params.poses.seed, kPoseNoiseStream);

  CalibrationTruth truth;
  truth.board = params.board;
  truth.corners = board.corners();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string name = poseDirectoryName(static_cast<int>(i));
    writeCapture((fs::path(directory) / name).string(),
                 renderCalibrationCapture(board, poses[i], params, noise_seeds()));
    truth.poses.push_back({name, poses[i], observeCorners(board, params.rig, poses[i])});
  }

  const fs::path truth_directory = fs::path(directory) / "truth";
  std::error_code error;
  fs::create_directories(truth_directory, error);
  if (error) {
    throw Error(truth_directory.string() + ": cannot create the directory: " + error.message());
  }
  writeRigCalibration((truth_directory / "rig.yaml").string(), params.rig);
  detail::writeBoardTruth(detail::boardTruthPath(directory), truth);
  return poses;
}

}  // namespace binpick::sim
