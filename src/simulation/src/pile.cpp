// generatePile: drop parts into a bin on a height field, render from above, record the truth.
#include "binpick/simulation/pile.hpp"

#include <algorithm>
#include <sstream>

#include "bin.hpp"
#include "binpick/io/error.hpp"
#include "height_field.hpp"
#include "mesh_geometry.hpp"
#include "random.hpp"
#include "rasterizer.hpp"
#include "sensor_noise.hpp"

namespace binpick::sim {
namespace {

constexpr double kCellSize = 0.001;  // height-field cell, metres
// Every surface point lies within this distance of a sample. Smaller than a cell, so that the
// sample marking a surface point falls in its cell or a neighbour; it then also bounds how deep
// two parts can interpenetrate through the height-field test.
constexpr double kSampleCoverage = 0.0004;
// Gap kept between a part's footprint and the inner walls, so rounding never puts it inside one.
constexpr double kWallClearance = 0.0005;

// Independent random streams under one seed: changing the sensor model never moves a part.
constexpr uint32_t kPlacementStream = 0;
constexpr uint32_t kSensorStream = 1;

// Camera above the floor centre looking down: a half-turn about x turns the bin's z up into the
// camera's z forward (and y into -y), then the floor centre sits camera_height ahead.
Eigen::Isometry3d cameraAboveBin(double camera_height) {
  Eigen::Isometry3d T_camera_bin = Eigen::Isometry3d::Identity();
  T_camera_bin.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  T_camera_bin.translation() = Eigen::Vector3d(0.0, 0.0, camera_height);
  return T_camera_bin;
}

// Every orientation of the part must fit between the walls, so the placement never has to give up.
void requirePartFitsInBin(const TriangleMesh& part, const PileParams& params) {
  const double diameter = 2.0 * detail::boundingRadius(part) + 2.0 * kWallClearance;
  if (diameter > std::min(params.bin_length, params.bin_width)) {
    std::ostringstream message;
    message << "generatePile: the part (" << diameter
            << " m across in its worst orientation) does not fit in a bin of " << params.bin_length
            << " x " << params.bin_width << " m";
    throw Error(message.str());
  }
}

std::vector<Eigen::Vector3f> rotated(const std::vector<Eigen::Vector3f>& points,
                                     const Eigen::Matrix3d& rotation) {
  const Eigen::Matrix3f r = rotation.cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(r * p);
  return out;
}

// A uniformly random x, y for which the footprint of `points` (relative to the part origin)
// stays inside the inner walls.
Eigen::Vector2d randomPositionInBin(const std::vector<Eigen::Vector3f>& points,
                                    const PileParams& params, detail::Rng& rng) {
  Eigen::Vector3f lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double x_limit = 0.5 * params.bin_length - kWallClearance;
  const double y_limit = 0.5 * params.bin_width - kWallClearance;
  const double x = detail::uniform(rng, -x_limit - lo.x(), x_limit - hi.x());
  const double y = detail::uniform(rng, -y_limit - lo.y(), y_limit - hi.y());
  return {x, y};
}

// Poses of the dropped parts in the bin frame, in drop order.
std::vector<Eigen::Isometry3d> dropParts(const TriangleMesh& part, const PileParams& params) {
  const std::vector<Eigen::Vector3f> samples = detail::surfaceSamples(part, kSampleCoverage);
  detail::HeightField field(params.bin_length, params.bin_width, kCellSize);
  detail::Rng rng = detail::makeRng(params.seed, kPlacementStream);
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(params.objects);
  for (int i = 0; i < params.objects; ++i) {
    const Eigen::Matrix3d rotation = detail::uniformRotation(rng);
    std::vector<Eigen::Vector3f> placed = rotated(samples, rotation);
    const Eigen::Vector2d xy = randomPositionInBin(placed, params, rng);
    const Eigen::Vector3f shift(static_cast<float>(xy.x()), static_cast<float>(xy.y()), 0.0f);
    for (auto& p : placed) p += shift;
    const detail::CellColumns columns = field.columnsOf(placed);
    const float lift = static_cast<float>(field.restingLift(columns));
    field.raise(columns, lift);
    Eigen::Isometry3d T_bin_object = Eigen::Isometry3d::Identity();
    T_bin_object.linear() = rotation;
    T_bin_object.translation() = Eigen::Vector3d(xy.x(), xy.y(), lift);
    poses.push_back(T_bin_object);
  }
  return poses;
}

// Visible pixels come from the pile render; unoccluded ones from drawing each part alone.
std::vector<ObjectTruth> objectTruths(const std::vector<RenderObject>& parts,
                                      const PinholeCamera& camera, const DepthImage& image) {
  std::vector<ObjectTruth> truths(parts.size());
  for (const int32_t id : image.instance) {
    if (id >= 0) ++truths[id].visible_pixels;
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ObjectTruth& truth = truths[i];
    truth.T_camera_object = parts[i].T_camera_object;
    truth.unoccluded_pixels = detail::countCoveredPixels(camera, parts[i]);
    truth.visible_fraction =
        truth.unoccluded_pixels > 0
            ? static_cast<double>(truth.visible_pixels) / truth.unoccluded_pixels
            : 0.0;
  }
  return truths;
}

constexpr int32_t kBinId = -2;

}  // namespace

PileScene generatePile(const TriangleMesh& part, const PileParams& params) {
  params.validate();
  if (part.empty()) throw Error("generatePile: the part mesh has no triangles");
  validateMesh(part, "generatePile part");
  requirePartFitsInBin(part, params);

  PileScene scene;
  scene.camera = params.camera;
  scene.T_camera_bin = cameraAboveBin(params.camera_height);

  std::vector<RenderObject> parts;
  for (const auto& T_bin_object : dropParts(part, params)) {
    parts.push_back({&part, scene.T_camera_bin * T_bin_object, static_cast<int32_t>(parts.size())});
  }
  const TriangleMesh bin =
      detail::makeBinMesh(params.bin_length, params.bin_width, params.bin_wall_height);
  // The bin goes last: on an exact depth tie the earlier object keeps the pixel, and a part lying
  // on the floor should own the pixels where it touches.
  std::vector<RenderObject> everything = parts;
  everything.push_back({&bin, scene.T_camera_bin, kBinId});

  DepthImage image = renderDepth(params.camera, everything);
  scene.objects = objectTruths(parts, params.camera, image);
  scene.cloud = depthToCloud(params.camera, image);
  detail::applySensorNoise(scene.cloud, params.depth_noise, params.dropout, params.seed,
                           kSensorStream);
  scene.instance = std::move(image.instance);
  return scene;
}

}  // namespace binpick::sim
