#pragma once
// What the cell shows its observers (the web view, binpick::web): its state, its capture source's
// health and a summary of each recent cycle. The service publishes a new CellReport at every
// change; observers hold an immutable copy (CellService::report()), so that reading it never
// waits for the cycle and the cycle never waits for a reader.
#include <Eigen/Geometry>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "binpick/cell/pick_cycle.hpp"
#include "binpick/core/orientation.hpp"
#include "binpick/picking/picking.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::cell {

enum class CellState : int32_t { Idle = 0, Capturing = 1, Computing = 2 };

// One pick as the robot is sent it, with why it was chosen.
struct PickSummary {
  int object = 0;  // index into the cycle's detections
  int grasp = 0;   // index into the recipe's grasps
  std::string grasp_name;
  Eigen::Isometry3d T_base_grasp = Eigen::Isometry3d::Identity();  // metres
  double tilt_deg = 0.0;
  double lean_deg = 0.0;   // off the face's normal, to keep the tool off a wall
  double clearance = 0.0;  // metres
  double rank = 0.0;       // the ranking value the picks were ordered by
  double score = 0.0;      // the detection's score
  double coverage = 0.0;   // the detection's share of visible model points fitted
};

struct CycleSummary {
  uint64_t number = 0;
  std::chrono::system_clock::time_point started;  // the capture's start
  std::string recipe;
  robot::Status status = robot::Status::Ok;
  std::string detail;  // why, when not ok
  std::size_t parts_detected = 0;
  std::size_t low_coverage = 0;  // detections below limits.min_pick_coverage: never offered
  int bin_points = 0;
  std::vector<PickSummary> picks;  // in pick order
  picking::PickRejections rejected;
  std::vector<std::string> undeliverable;  // planned picks the robot could not be sent
  CycleTimings timing_ms;
};

struct CaptureHealth {
  std::string mode;    // "replay" or "live"
  std::string source;  // the source's own description (the camera, the replayed path)
  uint64_t captures = 0;
  uint64_t failures = 0;  // captures that gave no image
  std::optional<std::chrono::system_clock::time_point> last_capture;
  bool last_ok = true;
  std::string last_error;           // of the last capture that failed
  std::string calibration_problem;  // "" when the rig calibration is loaded
  bool hand_eye = false;            // T_base_camera configured
};

constexpr std::size_t kReportedCycles = 50;  // recent cycles a report keeps

struct CellReport {
  CellState state = CellState::Idle;
  CycleStage stage = CycleStage::Reconstructing;  // meaningful while Computing
  std::string recipe;
  std::vector<std::string> recipes;
  uint64_t cycle = 0;             // the latest cycle's number (0: none yet)
  std::size_t picks_waiting = 0;  // picks of the latest cycle the robot has not fetched yet
  core::Orientation orientation = core::Orientation::Quaternion;  // the robot's convention
  CaptureHealth capture;
  std::optional<std::string> artefact_directory;  // where cycles are saved; none: not saved
  std::chrono::system_clock::time_point started;  // the service's start
  // Oldest first, at most kReportedCycles; shared between reports (it changes once a cycle).
  std::shared_ptr<const std::deque<CycleSummary>> recent = std::make_shared<const std::deque<CycleSummary>>();
};

}  // namespace binpick::cell
