#pragma once
// The benchmark's view of a pose estimator: every method gets the same scene cloud and the same
// bin crop, and returns its poses best first. The caller times detect() (the whole process:
// normals, matching, refinement); model preparation is offline and not timed, as in the paper.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "binpick/estimation/model.hpp"
#include "scene.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::bench {

// What every method is told about the part and the task.
struct MethodSetup {
  // binpick's prepared model (tau_d = 0.04): subsampled points and outward normals in the model
  // frame, diam(M) and the subsampling step d_dist. Peers train on these same points.
  const estimation::PreparedModel* model = nullptr;
  int max_objects = 20;          // detections wanted per scene
  int threads = 0;               // 0: all hardware threads (where the library lets us choose)
  std::string binpick_settings;  // a detection.yaml for the `binpick` method; empty: the defaults
};

// One scene: an organized cloud in the camera frame (camera at the origin looking along +z,
// metres, NaN where nothing was measured) and the bin's inside, outside which nothing is sought.
struct MethodInput {
  const io::PointCloud* cloud = nullptr;
  estimation::CropBox crop;
};

class PoseMethod {
 public:
  virtual ~PoseMethod() = default;
  virtual std::string name() const = 0;
  // T_camera_model of each detection, best first, at most setup.max_objects.
  virtual std::vector<Eigen::Isometry3f> detect(const MethodInput& input) const = 0;
};

// The finite points of the cloud inside the crop box, in cloud order: what the peers start from.
std::vector<Eigen::Vector3f> croppedPoints(const MethodInput& input);

}  // namespace binpick::bench
