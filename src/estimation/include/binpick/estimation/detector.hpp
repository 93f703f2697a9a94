#pragma once
// The whole estimation pipeline of Li & Hashimoto (2018): scene preparation, sparse voting,
// voxel verification, multiple selection (Algorithm 1) with ICP on visible points, and the
// original Drost method (voting over all pairs + pose clustering) as a baseline in the same
// engine. A Detector holds one prepared model; detect() is const and may run from several
// threads at once (each call uses its own working memory).
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "binpick/core/cancellation.hpp"
#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/model.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::estimation {

struct Detection {
  Eigen::Isometry3f T_camera_model = Eigen::Isometry3f::Identity();
  float score = 0.0f;         // Score_New / N_m at selection (eq. 4, less the free-space penalty);
                              // Drost: cluster votes / max votes
  float coverage = 0.0f;      // after ICP: share of the model points the camera should see that fit
  float icp_rmse = 0.0f;      // model units
  float seen_through = 0.0f;  // after ICP: share of the visible fine model points in front of the
                              // measured surface (free space the camera saw through)
  float twin_margin = 1.0f;   // after ICP: how much more of the range this pose explains than its
                              // best turned or slid twin, a share of its visible fine points (1: no
                              // twin came close); near 0 the range cannot tell the part from it
                              // turned; below 0 a twin explains more, but a turned one by less
                              // than the margin it needs to replace the pose, or a slid one (which
                              // never replaces it: near_symmetries.hpp); such a pose is not sure
  bool sure = true;           // twin_margin and coverage at least SelectionParams' sure_*: the
                              // sure detections come first
  uint32_t votes = 0;
  int icp_iterations = 0;
};

struct StageTimings {  // milliseconds
  double prepare_scene = 0, voting = 0, verification = 0, selection = 0, icp = 0, total = 0;
};

struct DetectionResult {
  std::vector<Detection> detections;  // in selection order
  StageTimings timing_ms;
  std::size_t scene_points = 0;                 // after subsampling
  std::size_t scene_points_without_normal = 0;  // subsampled points dropped: too few neighbours
  std::size_t scene_boundary_points = 0;        // boundary.enabled: subsampled outline points with a direction
  std::size_t candidates = 0;
  std::size_t refreshes = 0;              // eq. 4 evaluations during Algorithm 1
  std::size_t seen_through_rejected = 0;  // refined picks refused: the camera saw through them
};

// Why a scene gave the detector little to work with, for the user; empty when nothing is wrong.
// Today: most subsampled points had too few neighbours for a normal (a cloud far sparser than the
// model's step, or mostly isolated points).
std::string sceneWarning(const DetectionResult& result);

class Detector {
 public:
  Detector(PreparedModel model, DetectorParams params);
  DetectionResult detect(const io::PointCloud& scene_cloud) const;
  // The same with another crop box than the params' (a bin that moves between captures, or one
  // detector shared by several cells): no copy of the model. Once `cancel` is set (a deadline
  // passed) it throws core::Cancelled within a fraction of a second: it is checked between the
  // stages, per reference point in voting, per candidate in verification and before every ICP.
  DetectionResult detect(const io::PointCloud& scene_cloud, const std::optional<CropBox>& crop,
                         const core::CancelFlag* cancel = nullptr) const;
  const PreparedModel& model() const;
  const DetectorParams& params() const;

 private:
  // The model, the params and what the detector prepares from them once (the outline's model
  // side), in detector.cpp: immutable, so copies of a Detector share it.
  struct Prepared;
  std::shared_ptr<const Prepared> prepared_;
};

}  // namespace binpick::estimation
