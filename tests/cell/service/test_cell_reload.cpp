// Reloads and failure reports that land while a cycle is under way: the cycle runs on the settings
// that accepted its TRIGGER, a reload that would lose the calibration is refused, and a robot's
// FAILED counts whatever the cell is doing.
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "binpick/cell/cell_service.hpp"
#include "binpick/core/error.hpp"
#include "cell_scene.hpp"
#include "service_harness.hpp"

namespace binpick::cell {
namespace {

using robot::Command;
using robot::Status;
using testing::Cell;
using testing::cellConfigYaml;
using testing::cellScene;
using testing::kRobot;
using testing::request;
using testing::setupFor;
using testing::SlowSource;
using testing::withoutRigCalibration;

constexpr robot::ClientId kMonitor = 2;

// Runs a cycle whose last reply (a waiting NEXT) holds the cycle thread, then calls `in_window`
// while it is held: the cell is idle and the robot has its answer, but the cycle thread has not
// come back for the next TRIGGER yet. This is where binpickd crashed: a TRIGGER accepted here and
// a reload landing before the cycle thread took it up.
template <typename Action>
void actRightAfterACycle(Cell& cell, Action in_window) {
  cell.collector.holdAt(Command::NextPick);
  cell.service.handle(kRobot, request(Command::Trigger));
  cell.service.handle(kMonitor, request(Command::NextPick));  // waits for the cycle
  cell.collector.waitUntilHeld();
  in_window();
  cell.collector.release();
}

TEST(CellReload, ABrokenCalibrationReloadedRightAfterACycleIsRefusedAndTheTriggerRuns) {
  Cell cell(cellConfigYaml(cellScene()));
  const auto broken = setupFor(withoutRigCalibration(cellConfigYaml(cellScene())));
  ASSERT_FALSE(broken->reconstructor) << "the reloaded settings must lack a calibration";
  actRightAfterACycle(cell, [&] {
    cell.service.handle(kRobot, request(Command::Trigger));  // accepted: the cell is idle
    try {
      cell.service.reconfigure(broken, nullptr);
      ADD_FAILURE() << "a reload losing the calibration was taken";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find("rig calibration"), std::string::npos) << e.what();
    }
  });
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);  // the first cycle's TRIGGER
  EXPECT_EQ(cell.collector.next(kMonitor)->status, Status::Ok);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok) << "the TRIGGER accepted in the window";
  EXPECT_FALSE(cell.allPicks().empty());
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok) << "the running settings were kept";
}

TEST(CellReload, ACycleRunsOnTheSettingsThatAcceptedItsTrigger) {
  Cell cell(cellConfigYaml(cellScene()));
  const auto one_pick = setupFor(cellConfigYaml(cellScene(), "limits: {max_picks: 1}\n"));
  actRightAfterACycle(cell, [&] {
    cell.service.handle(kRobot, request(Command::Trigger));
    cell.service.reconfigure(one_pick, nullptr);  // valid: taken, for the cycles after this one
  });
  cell.collector.next(kRobot);
  cell.collector.next(kMonitor);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);
  EXPECT_GT(cell.allPicks().size(), 1u) << "the cycle accepted before the reload ran on the new settings";
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  EXPECT_EQ(cell.allPicks().size(), 1u);
}

TEST(CellReload, ACellWithoutCalibrationMayBeReloadedWithoutOneOrWithOne) {
  const std::string no_rig = withoutRigCalibration(cellConfigYaml(cellScene()));
  Cell cell(no_rig);
  EXPECT_NO_THROW(cell.service.reconfigure(setupFor(no_rig), nullptr));
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::CalibrationMissing);
  EXPECT_NO_THROW(cell.service.reconfigure(setupFor(cellConfigYaml(cellScene())), nullptr));
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
}

TEST(CellReload, LosingTheHandEyeIsALossToo) {
  CellSetup running;
  running.config.T_base_camera = Eigen::Isometry3d::Identity();
  CellSetup next;
  EXPECT_NE(calibrationLoss(running, next).find("hand-eye"), std::string::npos);
  EXPECT_EQ(calibrationLoss(next, running), "");
}

TEST(CellReload, ACycleOnSettingsWithoutCalibrationIsCalibrationMissingNotACrash) {
  const auto broken = setupFor(withoutRigCalibration(cellConfigYaml(cellScene())));
  const CycleOutcome outcome = processCapture(*broken, broken->recipes.at(0), io::Capture{}, {});
  EXPECT_EQ(outcome.status, Status::CalibrationMissing);
  EXPECT_EQ(outcome.detail, broken->calibration_problem);
}

// The robot reports a failed pick after it tried it, often after it already triggered the next
// cycle: the failure is kept for the avoid list of the cycle after.
TEST(CellReload, AFailureReportedWhileTheNextCycleRunsIsKept) {
  Cell cell(cellConfigYaml(cellScene(), "limits: {avoid_cycles: 1}\n"),
            std::make_unique<SlowSource>(std::chrono::milliseconds(300)));
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);  // cycle 1
  const robot::Reply first = cell.ask(request(Command::NextPick));
  ASSERT_EQ(first.status, Status::Ok);
  cell.service.handle(kRobot, request(Command::Trigger));  // cycle 2 captures for 300 ms
  const robot::Reply failed = cell.ask(request(Command::PickFailed), kMonitor);
  EXPECT_EQ(failed.status, Status::Ok);
  EXPECT_EQ(failed.integers, std::vector<int32_t>{first.integers.at(1)});
  const robot::Reply named = cell.ask(request(Command::PickFailed, std::to_string(first.integers.at(1))), kMonitor);
  EXPECT_EQ(named.status, Status::Ok);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);         // cycle 2's TRIGGER
  cell.allPicks();                                                    // cycle 2 took its avoid list before
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);  // cycle 3
  for (const robot::Reply& pick : cell.allPicks()) {
    EXPECT_GT((pick.T_base_tool->translation() - first.T_base_tool->translation()).norm(), 0.01)
        << "the failed part was offered again";
  }
}

// A TRIGGER accepted before the robot's FAILED numbers a cycle that keeps the avoid list it had,
// even when its thread reads the list after the failure: the part is avoided from the cycle after.
TEST(CellReload, AFailureReportedAfterATriggerWasAcceptedCountsFromTheCycleAfterIt) {
  Cell cell(cellConfigYaml(cellScene(), "limits: {avoid_cycles: 1}\n"));
  actRightAfterACycle(cell, [&] {
    cell.service.handle(kRobot, request(Command::Trigger));  // cycle 2, accepted, not yet taken up
    // From another connection: the monitor's NEXT reply is the one held.
    EXPECT_EQ(cell.ask(request(Command::PickFailed), kMonitor + 1).status, Status::Ok);  // cycle 1's pick
  });
  cell.collector.next(kRobot);
  const std::optional<robot::Reply> failed_pick = cell.collector.next(kMonitor);
  ASSERT_TRUE(failed_pick && failed_pick->status == Status::Ok);
  const Eigen::Vector3d where = failed_pick->T_base_tool->translation();
  const auto offers = [&where](const std::vector<robot::Reply>& picks) {
    return std::any_of(picks.begin(), picks.end(), [&](const robot::Reply& pick) {
      return (pick.T_base_tool->translation() - where).norm() < 0.01;
    });
  };
  ASSERT_EQ(cell.collector.next(kRobot)->status, Status::Ok);  // cycle 2's TRIGGER
  EXPECT_TRUE(offers(cell.allPicks())) << "cycle 2 was accepted before the failure: its avoid list is older";
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);  // cycle 3
  EXPECT_FALSE(offers(cell.allPicks())) << "the failed part was offered in the cycle after";
}

// docs/robot-protocol.md, "Reply shapes": no_cycle before any cycle ran; FAILED without an object
// before any pick was handed out is a bad argument; an object named then is the latest cycle's.
TEST(CellReload, FailedBeforeAnyPickFollowsTheProtocolTable) {
  Cell cell(cellConfigYaml(cellScene()));
  const robot::Reply before = cell.ask(request(Command::PickFailed));
  EXPECT_EQ(before.status, Status::NoCycle);
  EXPECT_EQ(before.integers, std::vector<int32_t>{-1});
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  for (int polls = 0; cell.ask(request(Command::Status)).integers.at(2) != 1; ++polls) {
    ASSERT_LT(polls, 600000) << "the cycle never finished";
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(cell.ask(request(Command::PickFailed)).status, Status::BadMessage);
  EXPECT_EQ(cell.ask(request(Command::PickFailed, "0")).status, Status::Ok);
}

}  // namespace
}  // namespace binpick::cell
