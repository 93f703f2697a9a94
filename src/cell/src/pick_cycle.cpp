#include "binpick/cell/pick_cycle.hpp"

#include <cmath>
#include <optional>

#include "binpick/core/stopwatch.hpp"
#include "binpick/picking/tool_collision.hpp"
#include "pick_delivery.hpp"

namespace binpick::cell {
namespace {

// The detections confident enough to send the robot to, in the base frame, and which detection
// each one is.
struct Candidates {
  std::vector<picking::DetectedPart> parts;
  std::vector<int> detection;
};

Candidates pickCandidates(const std::vector<Eigen::Isometry3d>& T_base_objects,
                          const estimation::DetectionResult& result, double min_coverage) {
  Candidates candidates;
  for (std::size_t i = 0; i < T_base_objects.size(); ++i) {
    if (result.detections[i].coverage < min_coverage) continue;
    const estimation::Detection& detection = result.detections[i];
    candidates.parts.push_back({T_base_objects[i], detection.score, detection.coverage, detection.sure});
    candidates.detection.push_back(static_cast<int>(i));
  }
  return candidates;
}

// Nothing detected: an empty bin, or parts the detector could not find.
void classifyEmpty(CycleOutcome& outcome, const CellSetup& setup) {
  const bool empty = outcome.bin_points <= setup.config.limits.empty_bin_max_points;
  outcome.status = empty ? robot::Status::BinEmpty : robot::Status::NoObjects;
  outcome.detail = std::to_string(outcome.bin_points) + " points in the bin";
}

// "12 parts detected: 2 with coverage below the minimum, 4 too tilted, ..." for a cycle without a
// pick. The first count is limits.min_pick_coverage's alone, not the detector's `sure` (which
// also weighs the turned twins): that one only orders the picks.
std::string unreachableDetail(std::size_t detected, std::size_t low_coverage, const picking::PickRejections& r) {
  return std::to_string(detected) + " parts detected: " + std::to_string(low_coverage) +
         " with coverage below the minimum, " + std::to_string(r.tilt) + " too tilted, " + std::to_string(r.bin) +
         " with the tool hitting the bin, " + std::to_string(r.cloud) + " with the tool hitting the measured cloud, " +
         std::to_string(r.seal) + " with no measured face under the cup, " + std::to_string(r.avoided) + " avoided, " +
         std::to_string(r.invalid) + " invalid";
}

}  // namespace

int countPointsInBin(const io::PointCloud& cloud, const Eigen::Isometry3d& T_base_camera, const picking::BinBox& bin,
                     double min_height) {
  const Eigen::Isometry3d T_bin_camera = bin.T_base_bin.inverse() * T_base_camera;
  const Eigen::Isometry3f transform = T_bin_camera.cast<float>();
  // Kept off the walls by as much as off the floor: wall points must not make a bin look full.
  const float half_length = static_cast<float>(bin.length / 2 - min_height);
  const float half_width = static_cast<float>(bin.width / 2 - min_height);
  int count = 0;
  for (const Eigen::Vector3f& point : cloud.points) {
    if (!point.allFinite()) continue;
    const Eigen::Vector3f p = transform * point;
    const bool inside = std::abs(p.x()) < half_length && std::abs(p.y()) < half_width && p.z() > min_height &&
                        p.z() < bin.wall_height * 2;
    count += inside ? 1 : 0;
  }
  return count;
}

CycleOutcome processCapture(const CellSetup& setup, const Recipe& recipe, const io::Capture& capture,
                            const std::vector<Eigen::Vector3d>& avoid, const core::CancelFlag* cancel,
                            const StageObserver& on_stage) {
  const auto begin = [&](CycleStage next) {
    if (on_stage) on_stage(next);
  };
  CycleOutcome outcome;
  if (!setup.reconstructor || !setup.config.T_base_camera || !recipe.detector) {
    outcome.status = robot::Status::CalibrationMissing;
    outcome.detail = setup.reconstructor ? (recipe.detector ? "no hand-eye T_base_camera is configured"
                                                            : "recipe " + recipe.name + " has no prepared model")
                                         : setup.calibration_problem;
    return outcome;
  }
  const Eigen::Isometry3d& T_base_camera = *setup.config.T_base_camera;
  core::Stopwatch stage;
  begin(CycleStage::Reconstructing);
  outcome.reconstruction = setup.reconstructor->reconstruct(capture, cancel);
  outcome.timing_ms.reconstruct = stage.lapMs();

  const estimation::Detector& detector = *recipe.detector;
  begin(CycleStage::Detecting);
  outcome.detection = detector.detect(outcome.reconstruction.cloud, detector.params().scene.crop, cancel);
  outcome.timing_ms.detect = stage.lapMs();
  core::throwIfCancelled(cancel, "before planning");
  begin(CycleStage::Planning);

  outcome.bin_points = countPointsInBin(outcome.reconstruction.cloud, T_base_camera, recipe.picking.bin,
                                        setup.config.limits.empty_bin_min_height);
  for (const estimation::Detection& d : outcome.detection.detections) {
    outcome.T_base_objects.push_back(T_base_camera * d.T_camera_model.cast<double>());
  }
  const Candidates candidates =
      pickCandidates(outcome.T_base_objects, outcome.detection, setup.config.limits.min_pick_coverage);
  const picking::MeasuredScene scene(outcome.reconstruction.cloud, T_base_camera);
  const io::PointCloud& cloud = outcome.reconstruction.cloud;
  const io::LensIntrinsics& camera = setup.reconstructor->rig().camera;
  std::optional<picking::MeasuredSurface> surface;  // the seal test reads the cloud through the camera's pixels
  if (cloud.width == camera.width && cloud.height == camera.height) surface.emplace(cloud, camera, T_base_camera);
  picking::PickPlan plan =
      picking::planPicks(candidates.parts, avoid, recipe.picking, &scene, surface ? &*surface : nullptr);
  if (plan.picks.size() > static_cast<std::size_t>(setup.config.limits.max_picks)) {
    plan.picks.resize(setup.config.limits.max_picks);
  }
  for (picking::Pick& pick : plan.picks) pick.object = candidates.detection[static_cast<std::size_t>(pick.object)];
  DeliverablePicks deliverable = deliverablePicks(std::move(plan.picks), setup.config.robot.codec);
  outcome.picks = std::move(deliverable.picks);
  outcome.undeliverable = std::move(deliverable.problems);
  outcome.rejected = plan.rejected;
  outcome.timing_ms.plan = stage.lapMs();

  if (outcome.T_base_objects.empty()) {
    classifyEmpty(outcome, setup);
  } else if (outcome.picks.empty() && !outcome.undeliverable.empty()) {
    outcome.status = robot::Status::Unreachable;
    outcome.detail = std::to_string(outcome.undeliverable.size()) +
                     " picks planned, none can be sent to the robot: " + outcome.undeliverable.front();
  } else if (outcome.picks.empty()) {
    outcome.status = robot::Status::Unreachable;
    outcome.detail = unreachableDetail(outcome.T_base_objects.size(),
                                       outcome.T_base_objects.size() - candidates.parts.size(), plan.rejected);
  }
  return outcome;
}

}  // namespace binpick::cell
