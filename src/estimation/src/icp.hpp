#pragma once
// Pose refinement (section III-D, last paragraph): point-to-plane ICP that moves only the model
// points the camera can see at the current pose (facing it and not hidden by the part itself)
// onto the scene, with a robust (Huber) weight. refine() is const: one PoseRefiner may serve many
// threads. Called outside a parallel region, refine() searches each iteration's correspondences on
// `threads` threads (0: all), with the same result on any number.
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/model.hpp"
#include "scene.hpp"

namespace binpick::estimation {

// How well a pose explains what the camera saw: its visible model points and those with a scene
// point within the fit distance. (What it contradicts: range_agreement.hpp.)
struct PoseFit {
  int visible = 0;
  int fitted = 0;
  float rmse = 0.0f;  // of the fitted points' plane residuals
  float coverage() const { return visible == 0 ? 0.0f : static_cast<float>(fitted) / static_cast<float>(visible); }
};

struct IcpResult {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  int iterations = 0;
  bool converged = false;
  PoseFit fit;  // of the final pose: coverage and residual
};

// Indices of model points seen by a camera at the origin when the model is at `pose`: facing the
// camera and nearest in their line of sight (a coarse z-buffer on the part itself).
std::vector<uint32_t> visibleModelPoints(const PreparedModel& model, const Eigen::Isometry3f& pose);
// The same for any sampling of the part's surface `step` apart (e.g. the model's fine surface);
// `centre` (model frame) sets the z-buffer's cell size.
std::vector<uint32_t> visibleSurfacePoints(const std::vector<Eigen::Vector3f>& points,
                                           const std::vector<Eigen::Vector3f>& normals, float step,
                                           const Eigen::Vector3f& centre, const Eigen::Isometry3f& pose);

// Holds a reference to `scene` (and an index of its points): the scene must outlive the refiner.
class PoseRefiner {
 public:
  PoseRefiner(const PreparedScene& scene, float step, IcpParams params, int threads = 0);
  ~PoseRefiner();
  PoseRefiner(const PoseRefiner&) = delete;
  PoseRefiner& operator=(const PoseRefiner&) = delete;

  IcpResult refine(const PreparedModel& model, const Eigen::Isometry3f& initial) const;
  // The same with at most `max_iterations` (a start already close to its answer).
  IcpResult refine(const PreparedModel& model, const Eigen::Isometry3f& initial, int max_iterations) const;
  // The fit of `pose`.
  PoseFit assess(const PreparedModel& model, const Eigen::Isometry3f& pose) const;
  // Scene points within `radius` of any model point at `pose` (each once, ascending).
  std::vector<uint32_t> scenePointsNear(const PreparedModel& model, const Eigen::Isometry3f& pose, float radius) const;

 private:
  struct Index;
  bool searchInParallel(std::size_t searches) const;
  const PreparedScene& scene_;
  float step_;
  IcpParams params_;
  float min_normal_cos_;  // cos of params_.max_normal_angle_deg
  int threads_;
  std::unique_ptr<Index> index_;
};

}  // namespace binpick::estimation
