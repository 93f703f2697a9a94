// emptyBin: the closed pick loop (emptying.hpp).
#include "binpick/emptying/emptying.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "cell_under_test.hpp"

namespace binpick::emptying {
namespace {

using robot::Command;
using robot::Status;

simulation::BinInterior binOf(const simulation::PileParams& pile) {
  return {pile.bin_length, pile.bin_width, pile.bin_wall_height};
}

io::PatternSetSpec patternsOf(const simulation::PileParams& pile) {
  io::PatternSetSpec patterns;
  patterns.projector_width = pile.rig.projector.width;
  patterns.projector_height = pile.rig.projector.height;
  return patterns;
}

// The loop's state between cycles: the pile as it lies, the cell, and what was seen last.
class EmptyingRun {
 public:
  EmptyingRun(const simulation::Part& part, const EmptyingParams& params)
      : part_(part),
        params_(params),
        physics_(part.mesh, binOf(params.pile), params.pile.physics, params.pile.seed),
        patterns_(patternsOf(params.pile)) {
    const simulation::PhysicsPile dropped = physics_.drop(params.pile.objects);
    report_.part = part.name;
    report_.gripper = picking::gripperTypeName(params.gripper.type);
    report_.objects = static_cast<int>(dropped.T_bin_object.size());
  }

  EmptyingReport run(const CycleObserver& observer) {
    int idle_cycles = 0;  // cycles in a row without a pick
    int last_failed_cycle = -1000;
    for (int cycle = 1; cycle <= params_.cycleLimit(); ++cycle) {
      CycleRecord record = runCycle(cycle);
      if (observer) observer(record);
      report_.cycles.push_back(record);
      if (record.status == robot::statusName(Status::BinEmpty)) {
        report_.end = EmptyingEnd::Empty;
        break;
      }
      if (record.pick && !record.pick->ok) last_failed_cycle = cycle;
      idle_cycles = record.pick ? 0 : idle_cycles + 1;
      const bool avoiding = cycle - last_failed_cycle <= cell_->avoidCycles();
      if (idle_cycles >= params_.patience && !avoiding) {
        report_.end = EmptyingEnd::Unreachable;
        break;
      }
    }
    finish();
    return report_;
  }

 private:
  CycleRecord runCycle(int cycle) {
    CycleRecord record;
    record.cycle = cycle;
    const std::vector<Eigen::Isometry3d> poses = physics_.poses();
    record.parts_before = static_cast<int>(poses.size());
    const core::Stopwatch render;
    showPile(poses, cycle);
    record.render_ms = render.elapsedMs();

    const robot::Reply trigger = cell().request(Command::Trigger);
    if (trigger.status != Status::Ok) {
      record.status = robot::statusName(trigger.status);
      record.detail = "TRIGGER answered " + record.status;
      record.parts_after = record.parts_before;
      return record;
    }
    const robot::Reply next = cell().request(Command::NextPick);
    const cell::CellSnapshot snapshot = cell().snapshot();
    record.status = robot::statusName(next.status);
    record.detail = snapshot.last_detail;
    record.detections = static_cast<int>(snapshot.last_parts_detected);
    record.cycle_ms =
        snapshot.last_timing_ms.reconstruct + snapshot.last_timing_ms.detect + snapshot.last_timing_ms.plan;
    if (next.status == Status::Ok && next.T_base_tool) record.pick = executePick(cycle, next, poses);
    record.parts_after = static_cast<int>(physics_.poses().size());
    return record;
  }

  void showPile(const std::vector<Eigen::Isometry3d>& poses, int cycle) {
    simulation::PhotometryParams photometry = params_.photometry;
    photometry.seed = params_.photometry.seed + static_cast<uint64_t>(cycle);  // new sensor noise each time
    simulation::PileCapture capture =
        simulation::renderPileCaptureAt(part_.mesh, params_.pile, poses, patterns_, photometry);
    if (!cell_) cell_ = std::make_unique<detail::CellUnderTest>(part_, params_, capture.scene.T_camera_bin);
    last_scene_ = std::move(capture.scene);
    cell_->show(simulation::recordedCapture(std::move(capture.images), params_.pile, patterns_, photometry,
                                            "binpick virtual cell, bin-emptying cycle " + std::to_string(cycle)));
  }

  // The simulated robot flies the commanded pick in the true scene: a part held leaves the bin; a
  // miss is reported to the cell, which then avoids that part.
  PickRecord executePick(int cycle, const robot::Reply& next, const std::vector<Eigen::Isometry3d>& poses) {
    PickRecord pick;
    pick.cycle = cycle;
    pick.T_base_grasp = *next.T_base_tool;
    pick.grasp = next.integers.size() > 2 ? next.integers[2] : -1;
    const auto& grasps = cell_->recipe().picking.grasps;
    if (pick.grasp >= static_cast<int>(grasps.size())) pick.grasp = -1;
    if (pick.grasp >= 0) pick.grasp_name = grasps[pick.grasp].name;

    const Eigen::Isometry3d T_bin_grasp = cell_->T_base_bin().inverse() * pick.T_base_grasp;
    const TrueScene truth(part_.mesh, poses, binOf(params_.pile));
    // Jaws open to the grasp's width and the cell's clearance each side, as the planner swept them.
    const auto& picking = cell_->recipe().picking;
    const double opening = pick.grasp >= 0 ? picking.jawOpeningFor(grasps[pick.grasp]) : 0.0;
    const PickJudgement judgement =
        judgePick(truth, T_bin_grasp, params_.gripper, params_.approach_distance, params_.truth, opening);
    pick.ok = judgement.ok;
    pick.reason = judgement.reason;
    // The part held, or on a miss the part the cup or a jaw touched first.
    const int part = judgement.object >= 0 ? judgement.object : judgement.touched;
    if (part >= 0) pick.T_base_part_true = cell_->T_base_bin() * poses[part];
    if (judgement.ok) {
      report_.escaped += static_cast<int>(physics_.remove(judgement.object).escaped.size());
      ++report_.picked;
    } else {
      ++report_.failed_picks;
      const int object = next.integers.size() > 1 ? next.integers[1] : -1;
      cell().request(Command::PickFailed, std::to_string(object));
    }
    return pick;
  }

  detail::CellUnderTest& cell() { return *cell_; }

  void finish() {
    const std::vector<Eigen::Isometry3d> poses = physics_.poses();
    for (std::size_t i = 0; i < poses.size(); ++i) {
      PartLeft left;
      left.index = static_cast<int>(i);
      left.T_base_part = cell_->T_base_bin() * poses[i];
      // The last capture shows the pile as it lies now unless that cycle's pick took a part.
      if (last_scene_.objects.size() == poses.size()) left.visible_fraction = last_scene_.objects[i].visible_fraction;
      const Eigen::Vector3d centre = poses[i].translation();  // bin frame: origin at the floor's centre
      left.wall_distance = std::min(0.5 * params_.pile.bin_length - std::abs(centre.x()),
                                    0.5 * params_.pile.bin_width - std::abs(centre.y()));
      report_.left.push_back(left);
    }
    report_.grasps = static_cast<int>(cell_->recipe().picking.grasps.size());
    std::vector<double> times;
    for (const CycleRecord& c : report_.cycles) {
      if (c.cycle_ms > 0.0) times.push_back(c.cycle_ms);
    }
    if (!times.empty()) {
      std::sort(times.begin(), times.end());
      const std::size_t n = times.size();
      report_.median_cycle_ms = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
      report_.max_cycle_ms = times.back();
    }
  }

  const simulation::Part& part_;
  EmptyingParams params_;
  simulation::PhysicsBin physics_;
  io::PatternSetSpec patterns_;
  std::unique_ptr<detail::CellUnderTest> cell_;
  simulation::PileScene last_scene_;
  EmptyingReport report_;
};

}  // namespace

EmptyingReport emptyBin(const simulation::Part& part, const EmptyingParams& params, const CycleObserver& observer) {
  params.validate();
  std::filesystem::create_directories(params.out_directory);
  EmptyingRun run(part, params);
  EmptyingReport report = run.run(observer);
  writeEmptyingJson((std::filesystem::path(params.out_directory) / "emptying.json").string(), report);
  return report;
}

}  // namespace binpick::emptying
