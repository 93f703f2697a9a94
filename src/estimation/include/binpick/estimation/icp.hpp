#pragma once
// Pose refinement (section III-D, last paragraph): point-to-plane ICP that moves only the model
// points the camera can see at the current pose (facing it and not hidden by the part itself)
// onto the scene, with a robust (Huber) weight. refine() is const: one PoseRefiner may serve many
// threads.
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

#include "binpick/estimation/model.hpp"
#include "binpick/estimation/scene.hpp"

namespace binpick::estimation {

struct IcpParams {
  int max_iterations = 30;
  float initial_max_distance_ratio = 2.0f;      // correspondence gate in steps, first iterations
  float final_max_distance_ratio = 0.75f;       // gate in steps once the pose has settled
  float huber_ratio = 0.25f;                    // Huber threshold on the plane residual, in steps
  float point_weight = 0.1f;                    // weight of the point-to-point distance beside the
                                                // plane residual (0: point-to-plane only)
  float convergence_translation_ratio = 1e-2f;  // stop when a step moves less (in steps: 0.04 mm
                                                // for a 100 mm part) ...
  float convergence_rotation_deg = 0.05f;       // ... and turns less than this
  float fit_distance_ratio = 0.75f;             // final coverage: a visible model point fits when a
                                                // scene point lies this close (in steps)
  bool visible_points_only = true;              // false: use all model points (for comparison)
  void validate() const;                        // throws core::Error naming the field
};

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
  float rmse = 0.0f;      // of the plane residuals of the final correspondences
  float coverage = 0.0f;  // fitted visible model points / visible model points, in [0, 1]
  int visible_points = 0;
  PoseFit fit;  // the final fit
};

// Indices of model points seen by a camera at the origin when the model is at `pose`: facing the
// camera and nearest in their line of sight (a coarse z-buffer on the part itself).
std::vector<uint32_t> visibleModelPoints(const PreparedModel& model, const Eigen::Isometry3f& pose);
// The same for any sampling of the part's surface `step` apart (e.g. the model's fine surface);
// `centre` (model frame) sets the z-buffer's cell size.
std::vector<uint32_t> visibleSurfacePoints(const std::vector<Eigen::Vector3f>& points,
                                           const std::vector<Eigen::Vector3f>& normals, float step,
                                           const Eigen::Vector3f& centre, const Eigen::Isometry3f& pose);

class PoseRefiner {
 public:
  PoseRefiner(const PreparedScene& scene, float step, IcpParams params);
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
  const PreparedScene& scene_;
  float step_;
  IcpParams params_;
  std::unique_ptr<Index> index_;
};

}  // namespace binpick::estimation
