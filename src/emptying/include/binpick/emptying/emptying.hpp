#pragma once
// The closed pick loop of the virtual cell: does the cell empty a bin?
//
// Drops the pile (Bullet), then repeats: render the capture of the pile as it lies -> one cycle of
// the cell service binpickd runs (CellService behind a RobotServer on the loopback interface, the
// settings read from a binpickd.yaml written for the run) -> the simulated robot, speaking the
// robot protocol over TCP (RobotConnection), triggers, takes the first pick and executes it against
// the truth (pick_truth.hpp) -> a failed pick is reported back with FAILED, so that the cell avoids
// that part -> a part held leaves the physics world and the pile re-settles -> next cycle. The run
// ends when binpickd reports the bin empty, when it has nothing to offer twice in a row with no
// part being avoided (the parts left are named), or after max_cycles.
//
// Deterministic for a seed up to the cell's timings. Runs one loop per call; concurrent calls need
// distinct out directories.
#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "binpick/emptying/pick_truth.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::emptying {

struct EmptyingParams {
  simulation::PileParams pile;              // objects, seed, bin, rig, physics, threads
  simulation::PhotometryParams photometry;  // its seed is varied per cycle: each capture has new noise
  picking::GripperParams gripper;
  double approach_distance = 0.10;  // metres: the straight approach the cell plans and the robot flies
  PickTruthParams truth;
  int max_cycles = 0;  // 0: 2 * objects + 10
  // Cycles in a row that offer no pick, while no failed part is avoided, before the run ends as
  // "unreachable" (a second look at the same pile with new sensor noise may find a part).
  int patience = 2;
  // Where the cell's files (settings, model, calibration), its saved cycles (overlay and
  // detections per cycle) and emptying.json go. Must be given.
  std::string out_directory;
  // The cell's web view (docs/binpickd.md, "Web view") on 127.0.0.1:web_port while the run lasts
  // (0: any free port); -1: none.
  int web_port = -1;
  void validate() const;  // throws core::Error naming the field
  int cycleLimit() const { return max_cycles > 0 ? max_cycles : 2 * pile.objects + 10; }
};

struct PickRecord {
  int cycle = 0;
  bool ok = false;
  std::string reason;  // the judge's verdict ("ok", "cup across an edge", ...)
  int grasp = -1;      // index into the recipe's grasps
  std::string grasp_name;
  Eigen::Isometry3d T_base_grasp = Eigen::Isometry3d::Identity();  // as commanded, metres
  std::optional<Eigen::Isometry3d> T_base_part_true;               // the part held; on a miss the one touched, if any
};

struct CycleRecord {
  int cycle = 0;
  std::string status;      // binpickd's answer to NEXT ("ok", "bin_empty", "unreachable", ...)
  std::string detail;      // why, when not ok
  int parts_before = 0;    // true parts in the bin when the capture was taken
  int parts_after = 0;     // after the pick and the re-settling
  int detections = 0;      // parts the cell detected
  double cycle_ms = 0.0;   // reconstruct + detect + plan, as the cell timed them
  double render_ms = 0.0;  // the virtual camera (not part of the cell's time)
  std::optional<PickRecord> pick;
};

enum class EmptyingEnd { Empty, Unreachable, MaxCycles };
std::string emptyingEndName(EmptyingEnd end);  // "empty" | "unreachable" | "max_cycles"

struct PartLeft {
  int index = 0;  // in the physics world's order
  Eigen::Isometry3d T_base_part = Eigen::Isometry3d::Identity();
  double visible_fraction = 0.0;  // in the last capture
  double wall_distance = 0.0;     // metres from the part's centre to the nearest inner wall of the bin
};

struct EmptyingReport {
  std::string part;
  std::string gripper;  // "suction" | "parallel"
  int objects = 0;      // parts in the bin after the drop
  int picked = 0;
  int failed_picks = 0;
  int escaped = 0;  // parts the re-settling pile threw out of the bin (not picked)
  EmptyingEnd end = EmptyingEnd::MaxCycles;
  std::vector<CycleRecord> cycles;
  std::vector<PartLeft> left;    // parts still in the bin at the end
  int grasps = 0;                // grasps the cell had for the part
  double median_cycle_ms = 0.0;  // over the cycles the cell processed
  double max_cycle_ms = 0.0;
  double clearedShare() const { return objects > 0 ? static_cast<double>(picked) / objects : 1.0; }
};

// Called after every cycle (for a progress line).
using CycleObserver = std::function<void(const CycleRecord&)>;

// Runs the loop for `part`. Throws core::Error on bad params, a part that cannot be dropped, or a
// cell that cannot start; a cycle's failure (a pick that misses, nothing detected) is a record.
EmptyingReport emptyBin(const simulation::Part& part, const EmptyingParams& params, const CycleObserver& observer = {});

// emptying.json: {"objects", "picked", "failed_picks", "cycles", "end", "cycle_ms": {"median", "max"},
// "picks": [{"cycle", "ok", "reason", "grasp", "T_base_grasp", "T_base_part_true"}], ...}.
void writeEmptyingJson(const std::string& path, const EmptyingReport& report);
// One line: "cleared 19/20 in 21 cycles, 0 failed picks, median cycle 0.8 s".
std::string summaryLine(const EmptyingReport& report);
// One line per cycle: "cycle 3: picked (grasp 2 ...), 17 left, cycle 0.52 s, render 1.4 s".
std::string cycleLine(const CycleRecord& cycle);

}  // namespace binpick::emptying
