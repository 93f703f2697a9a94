#pragma once
// One pick cycle after the capture: reconstruct the cloud, detect the parts, tell an empty bin
// from a bin whose parts were not found, plan the picks in the robot base frame with the tool
// tested against the measured cloud (tool_collision.hpp). Expected
// outcomes (nothing found, empty bin, nothing reachable) are statuses, not exceptions.
// Stateless functions: thread-safe.
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "binpick/cell/cell_setup.hpp"
#include "binpick/core/cancellation.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::cell {

struct CycleTimings {  // milliseconds
  double capture = 0, reconstruct = 0, detect = 0, plan = 0, total = 0;
};

struct CycleOutcome {
  robot::Status status = robot::Status::Ok;
  std::string detail;                             // why, when status is not ok
  std::vector<picking::Pick> picks;               // ordered, at most limits.max_picks
  picking::PickRejections rejected;               // the confident detections not picked, by reason
  std::vector<std::string> undeliverable;         // planned picks left out: which, and why
  std::vector<Eigen::Isometry3d> T_base_objects;  // every detection, base frame
  estimation::DetectionResult detection;
  reconstruction::Reconstruction reconstruction;
  int bin_points = 0;  // cloud points found inside the bin
  CycleTimings timing_ms;
};

// `avoid`: base-frame centres of objects the robot failed to pick. A setup without a
// reconstructor or T_base_camera (or a recipe without a detector) is a calibration_missing
// outcome, never a dereference: the caller checks it at TRIGGER, this checks it again. Picks whose NEXT reply the
// robot codec (setup.config.robot.codec) cannot encode are left out, each named in
// `undeliverable`: the robot could not be told them. Throws core::Error only for a capture the
// reconstruction refuses (a corrupt or mismatched capture), and core::Cancelled once `cancel` is
// set (checked between the stages and inside reconstruction and detection).
// `on_stage`, when given, is called as each stage begins (for observers: cheap and non-blocking).
enum class CycleStage { Reconstructing, Detecting, Planning };
using StageObserver = std::function<void(CycleStage)>;
CycleOutcome processCapture(const CellSetup& setup, const Recipe& recipe, const io::Capture& capture,
                            const std::vector<Eigen::Vector3d>& avoid, const core::CancelFlag* cancel = nullptr,
                            const StageObserver& on_stage = {});

// Points of `cloud` (camera frame) inside the bin's inner box, at least `min_height` off its floor
// and walls: tells "bin empty" from "nothing detected".
int countPointsInBin(const io::PointCloud& cloud, const Eigen::Isometry3d& T_base_camera, const picking::BinBox& bin,
                     double min_height);

}  // namespace binpick::cell
