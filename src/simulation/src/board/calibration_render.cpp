// renderCalibrationCapture: one board pose under every pattern of the set (or its white image).
#include <algorithm>

#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/simulation/calibration_sequence.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "board_albedo.hpp"
#include "sensor/pixel_lighting.hpp"

namespace binpick::simulation {
namespace {

constexpr int32_t kBoardId = 0;
constexpr int32_t kBackgroundId = 1;

// A square facing the camera (normal -z of its frame, which is the camera's), large enough to
// fill any usable field of view at its distance.
io::TriangleMesh wallMesh(double distance) {
  const auto half = static_cast<float>(2.0 * distance);
  io::TriangleMesh mesh;
  mesh.vertices = {{-half, -half, 0.0f}, {half, -half, 0.0f}, {half, half, 0.0f}, {-half, half, 0.0f}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  return mesh;
}

// The share of the nominal exposure that keeps the board's brightest pixel of the white image
// (full projector light, indirect light and ambient) at or below `max_counts`.
double exposureShare(const std::vector<PixelLighting>& lighting, const SensorGeometry& geometry, double max_counts) {
  if (max_counts <= 0.0) return 1.0;
  double peak = 0.0;
  for (std::size_t i = 0; i < lighting.size(); ++i) {
    if (geometry.object_id[i] != kBoardId) continue;
    const PixelLighting& l = lighting[i];
    peak = std::max(peak, static_cast<double>(l.ambient + l.direct + l.global));
  }
  return peak > max_counts ? max_counts / peak : 1.0;
}

// Every light contribution is proportional to the exposure time.
void scaleExposure(std::vector<PixelLighting>& lighting, double share) {
  const auto s = static_cast<float>(share);
  for (PixelLighting& l : lighting) {
    l.direct *= s;
    l.ambient *= s;
    l.global *= s;
  }
}

// The board's pixels, lit for the pose, at the exposure that keeps the board unsaturated.
struct LitBoard {
  int width = 0;
  int height = 0;
  std::vector<PixelLighting> lighting;
  double exposure_share = 1.0;
};

LitBoard lightBoard(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                    const CalibrationSequenceParams& params) {
  params.validate();
  std::vector<RenderObject> objects{{&board.mesh(), T_camera_board, kBoardId}};
  const io::TriangleMesh wall = wallMesh(params.background_distance);
  if (params.background_distance > 0.0) {
    Eigen::Isometry3d T_camera_wall = Eigen::Isometry3d::Identity();
    T_camera_wall.translation().z() = params.background_distance;
    objects.push_back({&wall, T_camera_wall, kBackgroundId});
  }
  const RayCaster scene(objects);
  const io::RigCalibration& rig = params.rig;
  const SensorGeometry geometry = computeSensorGeometry(rig, scene, params.geometry);
  const AlbedoFunction albedo = detail::boardPixelAlbedo(
      board, rig.camera, T_camera_board, kBoardId, params.pixel_samples, static_cast<float>(params.background_albedo));
  LitBoard lit{geometry.width, geometry.height, computePixelLighting(geometry, rig, params.photometry, albedo), 1.0};
  lit.exposure_share = exposureShare(lit.lighting, geometry, params.max_white_counts);
  scaleExposure(lit.lighting, lit.exposure_share);
  return lit;
}

PhotometryParams seeded(PhotometryParams photometry, uint64_t noise_seed) {
  photometry.seed = noise_seed;
  return photometry;
}

}  // namespace

io::Capture renderCalibrationCapture(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                                     const CalibrationSequenceParams& params, uint64_t noise_seed) {
  const LitBoard lit = lightBoard(board, T_camera_board, params);
  const PhotometryParams photometry = seeded(params.photometry, noise_seed);
  io::Capture capture;
  capture.images = renderPatternImages(lit.lighting, lit.width, lit.height, params.pattern_set, photometry);
  io::CaptureMetadata& m = capture.metadata;
  m.source = params.source;
  m.timestamp = io::utcTimestamp();
  m.image_width = lit.width;
  m.image_height = lit.height;
  m.bit_depth = photometry.bit_depth;
  m.exposure_us = params.exposure_us * lit.exposure_share;
  m.pattern_set = params.pattern_set;
  m.patterns = reconstruction::patternNames(params.pattern_set);
  return capture;
}

cv::Mat renderCalibrationWhiteImage(const CalibrationBoard& board, const Eigen::Isometry3d& T_camera_board,
                                    const CalibrationSequenceParams& params, uint64_t noise_seed) {
  const LitBoard lit = lightBoard(board, T_camera_board, params);
  return renderWhiteImage(lit.lighting, lit.width, lit.height, params.pattern_set,
                          seeded(params.photometry, noise_seed));
}

}  // namespace binpick::simulation
