// writeHandEyeSession: the views directory of a simulated session, truth last.
#include <filesystem>

#include "binpick/calibration/hand_eye_file.hpp"
#include "binpick/calibration/robot_pose_file.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/image_file.hpp"
#include "binpick/simulation/hand_eye_session.hpp"
#include "random.hpp"

namespace binpick::simulation {
namespace {

namespace fs = std::filesystem;

// Own random stream under the seed: one image-noise seed per view, in view order.
constexpr uint32_t kImageNoiseStream = 21;

// Never mix two sessions: the caller picks a new (or empty) directory.
void createFreshDirectory(const std::string& directory) {
  std::error_code error;
  if (fs::exists(directory, error) && !fs::is_empty(directory, error)) {
    throw core::Error(directory +
                      ": already exists and is not empty; write each hand-eye session to a"
                      " new directory");
  }
  fs::create_directories(directory, error);
  if (error) throw core::Error(directory + ": cannot create the directory: " + error.message());
}

calibration::HandEyeFile truthFile(const HandEyeSession& session) {
  calibration::HandEyeFile truth;
  truth.setup = session.setup;
  truth.T_mount_camera = session.T_mount_camera;
  truth.T_mount_board = session.T_mount_board;
  truth.method = "truth";
  truth.date = io::utcTimestamp();
  truth.views = static_cast<int>(session.views.size());
  return truth;
}

}  // namespace

HandEyeSession writeHandEyeSession(const std::string& directory, const HandEyeSessionParams& params) {
  const HandEyeSession session = simulateHandEyeSession(params);
  createFreshDirectory(directory);
  const CalibrationBoard board(params.board);
  detail::Rng noise_seeds = detail::makeRng(params.seed, kImageNoiseStream);
  calibration::RobotPoseFile poses;
  poses.orientation = params.orientation;
  for (const HandEyeSessionView& view : session.views) {
    const std::string image = (fs::path(directory) / (view.name + ".png")).string();
    io::writeImageFile(image, renderHandEyeImage(board, view.T_camera_board, params, noise_seeds()));
    poses.poses.push_back({view.name, view.T_base_flange, 0});
  }
  calibration::writeRobotPoseFile((fs::path(directory) / "poses.txt").string(), poses);
  io::writeRigCalibration((fs::path(directory) / "calib.yaml").string(), params.rig);
  calibration::writeHandEyeFile((fs::path(directory) / "truth" / "hand_eye.yaml").string(), truthFile(session));
  return session;
}

}  // namespace binpick::simulation
