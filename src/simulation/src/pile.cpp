// generatePile and viewPile: a pile in the bin, dropped or at given poses, seen by the rig, with its
// ground truth.
#include <cmath>
#include <string>
#include <utility>

#include "bin.hpp"
#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"
#include "binpick/simulation/pile.hpp"
#include "pile_view.hpp"
#include "render/object_visibility.hpp"
#include "sensor/mixed_pixels.hpp"
#include "sensor_noise.hpp"

namespace binpick::simulation {
namespace {

// Independent random streams under one seed: changing the sensor model never moves a part.
constexpr uint32_t kSensorStream = 1;

// Camera above the floor centre looking down: a half-turn about x turns the bin's z up into the
// camera's z forward (and y into -y), then the floor centre sits camera_height ahead.
Eigen::Isometry3d cameraAboveBin(double camera_height) {
  Eigen::Isometry3d T_camera_bin = Eigen::Isometry3d::Identity();
  T_camera_bin.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  T_camera_bin.translation() = Eigen::Vector3d(0.0, 0.0, camera_height);
  return T_camera_bin;
}

std::vector<Eigen::Isometry3d> partPoses(const PileScene& scene) {
  std::vector<Eigen::Isometry3d> poses;
  for (const ObjectTruth& o : scene.objects) poses.push_back(o.T_camera_object);
  return poses;
}

SensorGeometryParams geometryParams(const PileParams& params) {
  SensorGeometryParams geometry;
  geometry.threads = params.threads;
  return geometry;
}

void recordTruth(PileScene& scene, const SensorGeometry& geometry, const std::vector<ObjectVisibility>& visibility) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    scene.objects[i].visible_pixels = visibility[i].visible_lit_pixels;
    scene.objects[i].unoccluded_pixels = visibility[i].alone_lit_pixels;
    scene.objects[i].visible_fraction = visibility[i].visible_fraction;
  }
  scene.depth = geometry.depth;
  scene.instance = geometry.object_id;
  scene.exact_cloud = detail::exactCloud(geometry);
}

// The pile as the rig sees it: the scene, and what every camera pixel's centre ray hits, lit or
// not. The images trace the scene again at the pixels that straddle a depth edge.
struct PileView {
  RayCaster caster{std::vector<RenderObject>{}};
  SensorGeometry geometry;
};

PileView castRays(const io::TriangleMesh& part, const PileScene& scene, const PileParams& params,
                  std::vector<ObjectVisibility>* visibility = nullptr) {
  const io::TriangleMesh bin_mesh = detail::makeBinMesh(params.bin_length, params.bin_width, params.bin_wall_height);
  PileView view{RayCaster(detail::pileObjects(part, bin_mesh, partPoses(scene), scene.T_camera_bin)), {}};
  view.geometry = computeSensorGeometry(scene.rig, view.caster, geometryParams(params));
  if (visibility) {
    std::vector<int> parts(scene.objects.size());
    for (std::size_t i = 0; i < parts.size(); ++i) parts[i] = static_cast<int>(i);  // bin: last
    *visibility = computeObjectVisibilityOf(scene.rig, view.caster, view.geometry, parts, geometryParams(params));
  }
  return view;
}

void requireValidPart(const io::TriangleMesh& part, const char* caller) {
  if (part.empty()) throw core::Error(std::string(caller) + ": the part mesh has no triangles");
  io::validateMesh(part, std::string(caller) + " part");
}

// The scene at the given poses, handing out the view it cast so that images need not cast it
// again. Inputs already validated.
PileScene sceneAt(const io::TriangleMesh& part, const PileParams& params,
                  const std::vector<Eigen::Isometry3d>& T_bin_objects, PileView& view) {
  PileScene scene;
  scene.rig = params.rig;
  scene.T_camera_bin = cameraAboveBin(params.camera_height);
  for (const Eigen::Isometry3d& T_bin_object : T_bin_objects) {
    scene.objects.push_back({scene.T_camera_bin * T_bin_object, 0, 0, 0.0});
  }
  std::vector<ObjectVisibility> visibility;
  view = castRays(part, scene, params, &visibility);
  recordTruth(scene, view.geometry, visibility);
  scene.cloud = detail::measurableCloud(view.geometry, params.max_view_angle_deg);
  detail::applySensorNoise(scene.cloud, params.depth_noise, params.dropout, params.seed, kSensorStream);
  return scene;
}

// generatePile: the physics, then the view of the poses it gives.
PileScene generatePileWithView(const io::TriangleMesh& part, const PileParams& params, PileView& view) {
  params.validate();
  requireValidPart(part, "generatePile");
  const BinInterior bin{params.bin_length, params.bin_width, params.bin_wall_height};
  PhysicsPile physics = simulatePile(part, params.objects, bin, params.physics, params.seed);
  PileScene scene = sceneAt(part, params, physics.T_bin_object, view);
  scene.physics = std::move(physics);
  return scene;
}

PileScene viewPileWithView(const io::TriangleMesh& part, const PileParams& params,
                           const std::vector<Eigen::Isometry3d>& T_bin_objects, PileView& view) {
  params.validate();
  requireValidPart(part, "viewPile");
  PileScene scene = sceneAt(part, params, T_bin_objects, view);
  scene.physics.T_bin_object = T_bin_objects;
  scene.physics.settled = true;
  return scene;
}

std::vector<cv::Mat> imagesOf(const PileView& view, const PileScene& scene, const PileParams& params,
                              const io::PatternSetSpec& patterns, const PhotometryParams& photometry) {
  const AlbedoFunction albedo = detail::pileAlbedo(params);
  const SensorGeometry& geometry = view.geometry;
  const std::vector<PixelLighting> lighting = computePixelLighting(geometry, scene.rig, photometry, albedo);
  const MixedPixels mixed =
      detail::computeMixedPixels(scene.rig, view.caster, geometry, photometry, albedo, geometryParams(params));
  return renderPatternImages(lighting, geometry.width, geometry.height, patterns, photometry, mixed);
}

}  // namespace

PileScene generatePile(const io::TriangleMesh& part, const PileParams& params) {
  PileView view;
  return generatePileWithView(part, params, view);
}

std::vector<cv::Mat> renderPileImages(const io::TriangleMesh& part, const PileScene& scene, const PileParams& params,
                                      const io::PatternSetSpec& patterns, const PhotometryParams& photometry) {
  params.validate();
  return imagesOf(castRays(part, scene, params), scene, params, patterns, photometry);
}

PileCapture generatePileCapture(const io::TriangleMesh& part, const PileParams& params,
                                const io::PatternSetSpec& patterns, const PhotometryParams& photometry) {
  PileView view;
  PileCapture capture;
  capture.scene = generatePileWithView(part, params, view);
  capture.images = imagesOf(view, capture.scene, params, patterns, photometry);
  return capture;
}

PileScene viewPile(const io::TriangleMesh& part, const PileParams& params,
                   const std::vector<Eigen::Isometry3d>& T_bin_objects) {
  PileView view;
  return viewPileWithView(part, params, T_bin_objects, view);
}

PileCapture renderPileCaptureAt(const io::TriangleMesh& part, const PileParams& params,
                                const std::vector<Eigen::Isometry3d>& T_bin_objects, const io::PatternSetSpec& patterns,
                                const PhotometryParams& photometry) {
  PileView view;
  PileCapture capture;
  capture.scene = viewPileWithView(part, params, T_bin_objects, view);
  capture.images = imagesOf(view, capture.scene, params, patterns, photometry);
  return capture;
}

io::Capture recordedCapture(std::vector<cv::Mat> images, const PileParams& params, const io::PatternSetSpec& patterns,
                            const PhotometryParams& photometry, const std::string& source) {
  io::Capture capture;
  io::CaptureMetadata& m = capture.metadata;
  m.source = source;
  m.timestamp = io::utcTimestamp();
  m.image_width = params.rig.camera.width;
  m.image_height = params.rig.camera.height;
  m.bit_depth = photometry.bit_depth;
  m.exposure_us = 8000.0;  // nominal: the virtual sensor's counts do not depend on it
  m.pattern_set = patterns;
  m.patterns = reconstruction::patternNames(patterns);
  capture.images = std::move(images);
  return capture;
}

}  // namespace binpick::simulation

// PileParams::validate: every field checked, the message names the first bad one.
namespace binpick::simulation {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  core::requireField(ok, "PileParams", field, rule, value);
}

bool positive(double value) { return std::isfinite(value) && value > 0.0; }

constexpr int kMaxObjects = 10000;

}  // namespace

void PileParams::validate() const {
  require(objects >= 0 && objects <= kMaxObjects, "objects", "in [0, 10000]", objects);
  require(positive(bin_length), "bin_length", "positive", bin_length);
  require(positive(bin_width), "bin_width", "positive", bin_width);
  require(positive(bin_wall_height), "bin_wall_height", "positive", bin_wall_height);
  require(std::isfinite(camera_height) && camera_height > bin_wall_height, "camera_height",
          "finite and above the bin walls", camera_height);
  require(std::isfinite(depth_noise) && depth_noise >= 0.0, "depth_noise", ">= 0", depth_noise);
  require(std::isfinite(dropout) && dropout >= 0.0 && dropout < 1.0, "dropout", "in [0, 1)", dropout);
  require(std::isfinite(max_view_angle_deg) && max_view_angle_deg > 0.0 && max_view_angle_deg <= 90.0,
          "max_view_angle_deg", "in (0, 90]", max_view_angle_deg);
  require(std::isfinite(part_albedo) && part_albedo >= 0.0 && part_albedo <= 1.0, "part_albedo", "in [0, 1]",
          part_albedo);
  require(std::isfinite(bin_albedo) && bin_albedo >= 0.0 && bin_albedo <= 1.0, "bin_albedo", "in [0, 1]", bin_albedo);
  require(threads >= 0, "threads", ">= 0", threads);
  rig.validate();
  physics.validate("PileParams.physics");
}

}  // namespace binpick::simulation
