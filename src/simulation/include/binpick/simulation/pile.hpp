#pragma once
// A pile of identical parts in a bin, seen by the structured-light rig above it, with ground
// truth. Deterministic for a seed. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/io/capture.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/pattern_renderer.hpp"
#include "binpick/simulation/physics_pile.hpp"
#include "binpick/simulation/virtual_rig.hpp"

namespace binpick::simulation {

struct PileParams {
  int objects = 20;
  double bin_length = 0.40;       // metres, inner size along the bin's x
  double bin_width = 0.30;        // metres, inner size along the bin's y
  double bin_wall_height = 0.15;  // metres
  double camera_height = 0.90;    // metres from the bin floor to the camera centre
  // The measured cloud (PileScene::cloud): noise along the viewing ray, random dropouts, and the
  // steepest viewing angle at which a surface is still decoded.
  double depth_noise = 0.0003;  // metres, standard deviation
  double dropout = 0.0;         // fraction of measurable pixels randomly lost
  double max_view_angle_deg = 80.0;
  double part_albedo = 0.55;  // diffuse reflectance of the parts' surface
  double bin_albedo = 0.30;   // and of the bin's
  io::RigCalibration rig = makeVirtualRig();
  PhysicsParams physics;
  uint64_t seed = 1;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

struct ObjectTruth {
  Eigen::Isometry3d T_camera_object = Eigen::Isometry3d::Identity();
  int visible_pixels = 0;     // pixels where the camera sees it lit by the projector, in the pile
  int unoccluded_pixels = 0;  // the same were it alone at its pose
  // BOP's visib_fract with the projector's shadows: visible_pixels / unoccluded_pixels.
  double visible_fraction = 0.0;
};

struct PileScene {
  // What the sensor measures (an ideal decoder): organized, camera frame, the points both seen and
  // lit, with noise and dropouts; NaN elsewhere.
  io::PointCloud cloud;
  io::PointCloud exact_cloud;        // every surface point the camera sees, with normals; no noise
  std::vector<float> depth;          // exact camera z per pixel, NaN where nothing is seen
  std::vector<int32_t> instance;     // per pixel: object index, -2 the bin, -1 nothing
  std::vector<ObjectTruth> objects;  // objects[i] has instance id i
  io::RigCalibration rig;
  // Bin frame: origin at the centre of the floor's top face, x along bin_length, z up. The camera
  // looks straight down: bin x = camera x, bin y = camera -y, floor centre at camera z =
  // camera_height.
  Eigen::Isometry3d T_camera_bin = Eigen::Isometry3d::Identity();
  PhysicsPile physics;  // how the drop went
};

// Drops the parts into the bin (Bullet rigid bodies, physics_pile.hpp), then casts the rig's
// camera and projector rays into the scene. Throws core::Error on bad params or a part that
// cannot be dropped between the walls.
PileScene generatePile(const io::TriangleMesh& part, const PileParams& params);

// The camera images of `scene` under every pattern of `patterns` (patternSequence order).
std::vector<cv::Mat> renderPileImages(const io::TriangleMesh& part, const PileScene& scene, const PileParams& params,
                                      const io::PatternSetSpec& patterns, const PhotometryParams& photometry);

struct PileCapture {
  PileScene scene;
  std::vector<cv::Mat> images;  // one per pattern, patternSequence order
};

// generatePile and renderPileImages in one pass: the rig's rays are cast once for both.
PileCapture generatePileCapture(const io::TriangleMesh& part, const PileParams& params,
                                const io::PatternSetSpec& patterns, const PhotometryParams& photometry);

// The parts at the given poses (T_bin_object, bin frame), seen by the rig, with the same truth as
// generatePile gives for its own poses (generatePile is simulatePile, then this): no physics is
// run, the poses are taken as they are (a PhysicsBin gives them inside the bin and apart);
// params.objects and params.physics are not used. objects[i] is T_bin_objects[i];
// scene.physics holds the poses, settled, and no counts. No poses: the empty bin. Throws
// core::Error on bad params, a bad part mesh or a pose that is not a finite rigid transform.
PileScene viewPile(const io::TriangleMesh& part, const PileParams& params,
                   const std::vector<Eigen::Isometry3d>& T_bin_objects);

// viewPile and its pattern images in one pass, as generatePileCapture.
PileCapture renderPileCaptureAt(const io::TriangleMesh& part, const PileParams& params,
                                const std::vector<Eigen::Isometry3d>& T_bin_objects, const io::PatternSetSpec& patterns,
                                const PhotometryParams& photometry);

// The images as the rig would have recorded them: a Capture with its metadata (image size, bit
// depth, pattern set and names, a nominal exposure, the time now), ready for writeCapture or the
// decoder. `source` describes the scene in the metadata.
io::Capture recordedCapture(std::vector<cv::Mat> images, const PileParams& params, const io::PatternSetSpec& patterns,
                            const PhotometryParams& photometry, const std::string& source);

}  // namespace binpick::simulation
