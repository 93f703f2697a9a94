// writeCalibrationSequence: poses, one capture directory each, then the truth.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "binpick/core/error.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "calibration_truth.hpp"
#include "random.hpp"

namespace binpick::simulation {
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
    throw core::Error(directory +
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
    io::writeCapture((fs::path(directory) / name).string(),
                     renderCalibrationCapture(board, poses[i], params, noise_seeds()));
    truth.poses.push_back({name, poses[i], observeCorners(board, params.rig, poses[i])});
  }

  const fs::path truth_directory = fs::path(directory) / "truth";
  std::error_code error;
  fs::create_directories(truth_directory, error);
  if (error) {
    throw core::Error(truth_directory.string() + ": cannot create the directory: " + error.message());
  }
  io::writeRigCalibration((truth_directory / "rig.yaml").string(), params.rig);
  detail::writeBoardTruth(detail::boardTruthPath(directory), truth);
  return poses;
}

}  // namespace binpick::simulation

// CalibrationSequenceParams::validate: its own fields, then every nested struct's, each error
// prefixed with the member it came from.
namespace binpick::simulation {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "CalibrationSequenceParams", field, rule, value);
}

void nested(const char* member, const std::function<void()>& validate) {
  try {
    validate();
  } catch (const core::Error& e) {
    throw core::Error(std::string("CalibrationSequenceParams.") + member + ": " + e.what());
  }
}

bool finite(double v) { return std::isfinite(v); }

// The farthest a point of the board can be from the camera: its centre's distance plus the
// half diagonal of its outline (and its thickness).
double farthestBoardPoint(const CalibrationSequenceParams& p) {
  const double x = p.board.squares_x * p.board.square_size + 2.0 * p.board.margin;
  const double y = p.board.squares_y * p.board.square_size + 2.0 * p.board.margin;
  return p.poses.max_distance + 0.5 * std::hypot(x, y) + p.board.thickness;
}

}  // namespace

void CalibrationSequenceParams::validate() const {
  nested("board", [&] { board.validate(); });
  nested("poses", [&] { poses.validate(); });
  nested("rig", [&] { rig.validate(); });
  nested("pattern_set", [&] { pattern_set.validate(); });
  nested("photometry", [&] { photometry.validate(); });
  nested("geometry", [&] { geometry.validate(); });
  require(pattern_set.projector_width == rig.projector.width, "pattern_set.projector_width",
          "the rig projector's width", pattern_set.projector_width);
  require(pattern_set.projector_height == rig.projector.height, "pattern_set.projector_height",
          "the rig projector's height", pattern_set.projector_height);
  require(finite(texel_size) && texel_size > 0.0, "texel_size", "positive", texel_size);
  require(pixel_samples >= 1 && pixel_samples <= 16, "pixel_samples", "in [1, 16]", pixel_samples);
  require(
      finite(background_distance) && (background_distance == 0.0 || background_distance > farthestBoardPoint(*this)),
      "background_distance", "0 (no wall) or beyond the farthest board point", background_distance);
  require(finite(background_albedo) && background_albedo >= 0.0 && background_albedo <= 1.0, "background_albedo",
          "in [0, 1]", background_albedo);
  require(finite(exposure_us) && exposure_us > 0.0, "exposure_us", "positive", exposure_us);
  require(finite(max_white_counts) && max_white_counts >= 0.0, "max_white_counts", ">= 0 (0: off)", max_white_counts);
}

}  // namespace binpick::simulation
