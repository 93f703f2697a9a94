// Random board poses in the rig's working volume, each seen whole by camera and projector.
#include <cmath>
#include <sstream>

#include "binpick/core/error.hpp"
#include "binpick/simulation/calibration_board.hpp"
#include "random.hpp"

namespace binpick::simulation {
namespace {

// Own random stream under the seed (see random.hpp), apart from piles and image noise.
constexpr uint32_t kBoardPoseStream = 10;
constexpr double kTwoPi = 6.28318530717958647692;
constexpr double kHalfPi = 1.57079632679489661923;

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "BoardPoseParams", field, rule, value);
}

bool finite(double v) { return std::isfinite(v); }

// One draw. The board starts facing the camera (its frame aligned with the camera's: the print,
// seen from -z, faces the camera), is turned about its normal, tilted about an axis in the image
// plane, and its centre put at `distance` along a direction off the camera axis.
Eigen::Isometry3d drawPose(const CalibrationBoard& board, const BoardPoseParams& p, detail::Rng& rng) {
  const double distance = detail::uniform(rng, p.min_distance, p.max_distance);
  const double offset_x = detail::uniform(rng, -p.max_offset, p.max_offset);
  const double offset_y = detail::uniform(rng, -p.max_offset, p.max_offset);
  // sqrt: tilts spread evenly over the cap of directions, so that strong tilts (what a
  // calibration learns most from) are not rarer than weak ones.
  const double tilt = p.max_tilt * std::sqrt(detail::uniform01(rng));
  const double tilt_axis = detail::uniform(rng, 0.0, kTwoPi);
  const double spin = detail::uniform(rng, -p.max_in_plane_rotation, p.max_in_plane_rotation);

  const Eigen::Vector3d axis(std::cos(tilt_axis), std::sin(tilt_axis), 0.0);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(tilt, axis).matrix() * Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Vector2d centre_2d = board.printedFace().center();
  const Eigen::Vector3d centre_board(centre_2d.x(), centre_2d.y(), 0.0);
  const Eigen::Vector3d centre_camera = distance * Eigen::Vector3d(offset_x, offset_y, 1.0);
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();
  T_camera_board.linear() = rotation;
  T_camera_board.translation() = centre_camera - rotation * centre_board;
  return T_camera_board;
}

}  // namespace

void BoardPoseParams::validate() const {
  require(count >= 0, "count", ">= 0", count);
  require(finite(min_distance) && min_distance > 0.0, "min_distance", "positive", min_distance);
  require(finite(max_distance) && max_distance >= min_distance, "max_distance", ">= min_distance", max_distance);
  require(finite(max_offset) && max_offset >= 0.0, "max_offset", ">= 0", max_offset);
  require(finite(max_tilt) && max_tilt >= 0.0 && max_tilt < kHalfPi, "max_tilt", "in [0, pi/2) radians", max_tilt);
  require(finite(max_in_plane_rotation) && max_in_plane_rotation >= 0.0, "max_in_plane_rotation", ">= 0",
          max_in_plane_rotation);
  require(finite(image_margin) && image_margin >= 0.0, "image_margin", ">= 0", image_margin);
  require(finite(min_facing_cosine) && min_facing_cosine >= 0.0 && min_facing_cosine < 1.0, "min_facing_cosine",
          "in [0, 1)", min_facing_cosine);
  require(max_attempts >= 1, "max_attempts", ">= 1", max_attempts);
}

std::vector<Eigen::Isometry3d> randomBoardPoses(const CalibrationBoard& board, const io::RigCalibration& rig,
                                                const BoardPoseParams& params) {
  params.validate();
  rig.validate();
  detail::Rng rng = detail::makeRng(params.seed, kBoardPoseStream);
  std::vector<Eigen::Isometry3d> poses;
  while (static_cast<int>(poses.size()) < params.count) {
    int attempt = 0;
    for (; attempt < params.max_attempts; ++attempt) {
      const Eigen::Isometry3d pose = drawPose(board, params, rng);
      if (boardInView(board, rig, pose, params.image_margin, params.min_facing_cosine)) {
        poses.push_back(pose);
        break;
      }
    }
    if (attempt == params.max_attempts) {
      std::ostringstream message;
      message << "randomBoardPoses: no board pose in " << params.max_attempts
              << " draws keeps the whole board inside the camera and projector images; make"
                 " the board smaller or the working volume (BoardPoseParams) narrower";
      throw core::Error(message.str());
    }
  }
  return poses;
}

}  // namespace binpick::simulation
