#pragma once
// A pile of identical parts in a bin, seen by a depth camera above it, with ground truth.
// Deterministic for a seed. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "binpick/simulation/depth_renderer.hpp"

namespace binpick::sim {

struct PileParams {
  int objects = 20;
  double bin_length = 0.40;      // metres, inner size along world x
  double bin_width = 0.30;       // metres, inner size along world y
  double bin_wall_height = 0.15; // metres
  double camera_height = 0.90;   // metres from the bin floor to the camera centre
  double depth_noise = 0.0003;   // metres, standard deviation along the viewing ray
  double dropout = 0.0;          // fraction of valid pixels randomly lost
  PinholeCamera camera;
  uint64_t seed = 1;
  void validate() const;
};

struct ObjectTruth {
  Eigen::Isometry3d T_camera_object = Eigen::Isometry3d::Identity();
  int visible_pixels = 0;        // pixels showing this object in the pile
  int unoccluded_pixels = 0;     // pixels it would cover alone at the same pose
  // Visible share of what the camera could see of it (BOP's visib_fract): visible/unoccluded.
  double visible_fraction = 0.0;
};

struct PileScene {
  PointCloud cloud;                 // organized, camera frame, noisy
  // Per pixel: object index, -2 bin, -1 nothing. From the noise-free render: a pixel lost to
  // dropout keeps its label.
  std::vector<int32_t> instance;
  std::vector<ObjectTruth> objects;  // in drop order: objects[i] has instance id i
  PinholeCamera camera;
  // Bin frame: origin at the centre of the floor's top face, x along bin_length, z up. The camera
  // looks straight down: bin x = camera x, bin y = camera -y, floor centre at camera z =
  // camera_height.
  Eigen::Isometry3d T_camera_bin = Eigen::Isometry3d::Identity();
};

// Drops the parts one by one onto a height field of the bin and what lies in it (no physics:
// each part keeps its random orientation and rests where its lowest point first touches), then
// renders the scene from above. The part is rotated about its model origin, and each
// ObjectTruth::T_camera_object places that origin. Every part stays inside the inner walls; throws
// binpick::Error on bad params or a part too large to fit the bin in every orientation.
PileScene generatePile(const TriangleMesh& part, const PileParams& params);

}  // namespace binpick::sim
