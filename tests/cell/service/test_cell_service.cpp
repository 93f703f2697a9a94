// The cell service on a replayed bin of the virtual cell: requests in, replies out, checked
// against the truth of the pile.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "binpick/cell/cell_service.hpp"
#include "cell_scene.hpp"
#include "service_harness.hpp"
#include "temp_directory_test.hpp"

namespace binpick::cell {
namespace {

namespace fs = std::filesystem;
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

// Whether `T_base_grasp` is one of the recipe's grasps on one of the true parts, within what a
// suction gripper forgives (8 mm, 8 degrees; the paper counts a pose correct within diam/10,
// here 9.6 mm, and 10 degrees).
bool onSomeTruePart(const Eigen::Isometry3d& T_base_grasp, const Recipe& recipe) {
  for (const Eigen::Isometry3d& T_base_object : cellScene().T_base_objects) {
    for (const picking::Grasp& grasp : recipe.picking.grasps) {
      const Eigen::Isometry3d expected = T_base_object * grasp.T_model_grasp;
      const double mm = (expected.translation() - T_base_grasp.translation()).norm() * 1000;
      const double deg = Eigen::AngleAxisd(expected.linear().transpose() * T_base_grasp.linear()).angle() * 180 / M_PI;
      if (mm < 8.0 && deg < 8.0) return true;
    }
  }
  return false;
}

TEST(CellService, ACycleHandsOutPicksOnTheTrueParts) {
  Cell cell(cellConfigYaml(cellScene()));
  const robot::Reply triggered = cell.ask(request(Command::Trigger));
  EXPECT_EQ(triggered.status, Status::Ok);
  ASSERT_EQ(triggered.integers.size(), 1u);
  EXPECT_EQ(triggered.integers[0], 1);  // cycle number

  const std::vector<robot::Reply> picks = cell.allPicks();
  ASSERT_GE(picks.size(), 4u) << "12 parts in the bin";
  double previous_height = 1e9;
  for (std::size_t i = 0; i < picks.size(); ++i) {
    ASSERT_TRUE(picks[i].T_base_tool.has_value());
    EXPECT_EQ(picks[i].integers.at(0), static_cast<int32_t>(picks.size() - i - 1)) << "picks remaining";
    EXPECT_TRUE(onSomeTruePart(*picks[i].T_base_tool, cell.setup->recipes[0])) << "pick " << i;
    const double height = picks[i].T_base_tool->translation().z();
    EXPECT_LE(height, previous_height + 1e-9) << "highest first";
    previous_height = height;
  }
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::NoMorePicks);
  const robot::Reply status = cell.ask(request(Command::Status));
  EXPECT_EQ(status.integers, (std::vector<int32_t>{0, 0, 1}));  // idle, recipe 0, one cycle done
}

TEST(CellService, NextWaitsForTheRunningCycle) {
  Cell cell(cellConfigYaml(cellScene()));
  cell.service.handle(kRobot, request(Command::Trigger));
  cell.service.handle(2, request(Command::NextPick));  // a second client asks before the capture is done
  const auto next = cell.collector.next(2);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->status, Status::Ok);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);  // the TRIGGER's own reply came too
}

TEST(CellService, BusyWhileACycleRunsAndNoCycleBeforeTheFirst) {
  Cell cell(cellConfigYaml(cellScene()));
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::NoCycle);
  EXPECT_EQ(cell.ask(request(Command::PickFailed)).status, Status::NoCycle);
  cell.service.handle(kRobot, request(Command::Trigger));
  EXPECT_EQ(cell.ask(request(Command::Trigger), 2).status, Status::Busy);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);
}

TEST(CellService, AFailedPickIsAvoidedInTheNextCycle) {
  Cell cell(cellConfigYaml(cellScene()));
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  const robot::Reply first = cell.ask(request(Command::NextPick));
  ASSERT_EQ(first.status, Status::Ok);
  const robot::Reply failed = cell.ask(request(Command::PickFailed));
  EXPECT_EQ(failed.status, Status::Ok);
  EXPECT_EQ(failed.integers.at(0), first.integers.at(1));  // the object of the last pick
  EXPECT_EQ(cell.ask(request(Command::PickFailed, "999")).status, Status::BadMessage);

  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);  // the same bin again (replay loops)
  for (const robot::Reply& pick : cell.allPicks()) {
    EXPECT_GT((pick.T_base_tool->translation() - first.T_base_tool->translation()).norm(), 0.01);
  }
}

TEST(CellService, APartFailingAgainIsAvoidedTwiceAsLong) {
  Cell cell(cellConfigYaml(cellScene(), "limits: {avoid_cycles: 1}\n"));
  // Whether the first pick's part is offered in the next cycle (the same bin: replay loops).
  const auto offeredAgain = [&cell](const Eigen::Vector3d& where) {
    EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
    for (const robot::Reply& pick : cell.allPicks()) {
      if ((pick.T_base_tool->translation() - where).norm() < 0.01) return true;
    }
    return false;
  };
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);  // cycle 1
  const robot::Reply first = cell.ask(request(Command::NextPick));
  ASSERT_EQ(first.status, Status::Ok);
  const Eigen::Vector3d where = first.T_base_tool->translation();
  ASSERT_EQ(cell.ask(request(Command::PickFailed)).status, Status::Ok);  // avoided in cycle 2
  EXPECT_FALSE(offeredAgain(where));                                     // cycle 2
  EXPECT_TRUE(offeredAgain(where));                                      // cycle 3: its first pick
  ASSERT_EQ(cell.ask(request(Command::PickFailed, std::to_string(first.integers.at(1)))).status, Status::Ok);
  EXPECT_FALSE(offeredAgain(where));  // cycle 4
  EXPECT_FALSE(offeredAgain(where));  // cycle 5: a second failure doubles the time
  EXPECT_TRUE(offeredAgain(where));   // cycle 6
}

TEST(CellService, AnEmptyBinIsToldFromPartsNotFound) {
  Cell cell(cellConfigYaml(cellScene(), "", cellScene().empty_capture));
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::BinEmpty);
}

TEST(CellService, WithoutCalibrationTriggerSaysSo) {
  std::string no_hand_eye = cellConfigYaml(cellScene());
  no_hand_eye.erase(no_hand_eye.find("hand_eye:"), no_hand_eye.find("recipes:") - no_hand_eye.find("hand_eye:"));
  Cell cell(no_hand_eye);
  const robot::Reply refused = cell.ask(request(Command::Trigger));
  EXPECT_EQ(refused.status, Status::CalibrationMissing);
  EXPECT_EQ(refused.integers, std::vector<int32_t>{0}) << "no cycle started";

  Cell other(withoutRigCalibration(cellConfigYaml(cellScene())));
  EXPECT_FALSE(other.setup->calibration_problem.empty());
  EXPECT_EQ(other.ask(request(Command::Trigger)).status, Status::CalibrationMissing);
  EXPECT_EQ(other.ask(request(Command::Ping)).status, Status::Ok);  // the service still serves
}

class CellServiceFiles : public test::TempDirectoryTest {};

TEST_F(CellServiceFiles, ACorruptRecordingIsNoImageAndTheNextCycleWorks) {
  const fs::path bad = pathOf("bad");
  fs::copy(cellScene().capture, bad, fs::copy_options::recursive);
  fs::path image;
  for (const auto& entry : fs::directory_iterator(bad / "images")) image = entry.path();
  std::ofstream(image, std::ios::trunc) << "not a png";
  Cell cell(cellConfigYaml(cellScene(), "", root()));  // replays bad/ then ... only bad/
  const robot::Reply triggered = cell.ask(request(Command::Trigger));
  EXPECT_EQ(triggered.status, Status::NoImage);
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::NoImage);
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::NoImage);  // still serving
}

TEST(CellService, ACaptureThatMissesItsDeadlineIsATimeout) {
  Cell cell(cellConfigYaml(cellScene(), "limits: {capture_timeout_ms: 100}\n"),
            std::make_unique<SlowSource>(std::chrono::milliseconds(1500)));
  cell.service.handle(kRobot, request(Command::Trigger));
  cell.service.handle(kRobot, request(Command::NextPick));
  const auto triggered = cell.collector.next(kRobot, std::chrono::milliseconds(1200));
  ASSERT_TRUE(triggered.has_value()) << "answered at the deadline, not when the capture came";
  EXPECT_EQ(triggered->status, Status::Timeout);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Timeout);      // the waiting NEXT too
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Busy);  // the late capture still runs
}

TEST(CellService, RecipesAreSelectedByNameOrIndex) {
  Cell cell(cellConfigYaml(cellScene()));
  const robot::Reply selected = cell.ask(request(Command::SelectModel, "second"));
  EXPECT_EQ(selected.status, Status::Ok);
  EXPECT_EQ(selected.integers, std::vector<int32_t>{1});
  EXPECT_EQ(cell.ask(request(Command::SelectModel, "0")).integers, std::vector<int32_t>{0});
  EXPECT_EQ(cell.ask(request(Command::SelectModel, "nut")).status, Status::UnknownModel);
  EXPECT_EQ(cell.ask(request(Command::Trigger, "nut")).status, Status::UnknownModel);
  EXPECT_EQ(cell.ask(request(Command::Status)).integers.at(1), 0);
}

TEST(CellService, APoseIsNotServedAndChangesNothing) {
  Cell cell(cellConfigYaml(cellScene()));
  robot::Request pose = request(Command::Pose);
  pose.T_base_flange = Eigen::Isometry3d::Identity();
  const robot::Reply refused = cell.ask(pose);
  EXPECT_EQ(refused.command, Command::Pose);
  EXPECT_EQ(refused.status, Status::UnknownCommand);
  EXPECT_TRUE(refused.integers.empty());
  const robot::Reply status = cell.ask(request(Command::Status));
  EXPECT_EQ(status.status, Status::Ok);
  EXPECT_EQ(status.integers, (std::vector<int32_t>{0, 0, 0}));  // idle, first recipe, no cycle
}

TEST(CellService, StoppingDuringACycleAnswersTheRobot) {
  Cell cell(cellConfigYaml(cellScene()), std::make_unique<SlowSource>(std::chrono::milliseconds(300)));
  cell.service.handle(kRobot, request(Command::Trigger));
  cell.service.stop();
  const auto reply = cell.collector.next(kRobot, std::chrono::milliseconds(0));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, Status::InternalError);
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Busy);  // stopped: refuses new cycles
}

TEST(CellService, AReloadDuringACycleTakesEffectAfterIt) {
  Cell cell(cellConfigYaml(cellScene()));
  cell.service.handle(kRobot, request(Command::Trigger));
  auto reloaded = setupFor(cellConfigYaml(cellScene(), "limits: {max_picks: 1}\n"));
  cell.service.reconfigure(reloaded, nullptr);
  EXPECT_EQ(cell.collector.next(kRobot)->status, Status::Ok);
  cell.allPicks();
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  EXPECT_EQ(cell.allPicks().size(), 1u);
}

// A robot program reads a fixed number of fields: each command's reply carries the same integers
// whatever its status (counts 0 and ids -1 when there is nothing to tell), except
// unknown_command and bad_message, which carry none (docs/robot-protocol.md, "Reply shapes").
TEST(CellService, EachCommandAnswersWithOneShapeWhateverTheStatus) {
  using Ints = std::vector<int32_t>;
  Cell cell(cellConfigYaml(cellScene()));
  const robot::Reply no_cycle = cell.ask(request(Command::NextPick));
  EXPECT_EQ(no_cycle.status, Status::NoCycle);
  EXPECT_EQ(no_cycle.integers, (Ints{0, -1, -1}));
  const robot::Reply failed_before = cell.ask(request(Command::PickFailed));
  EXPECT_EQ(failed_before.status, Status::NoCycle);
  EXPECT_EQ(failed_before.integers, Ints{-1}) << "no pick handed out";
  EXPECT_EQ(cell.ask(request(Command::PickFailed, "7")).integers, Ints{7}) << "the object named";
  const robot::Reply unknown_trigger = cell.ask(request(Command::Trigger, "nut"));
  EXPECT_EQ(unknown_trigger.status, Status::UnknownModel);
  EXPECT_EQ(unknown_trigger.integers, Ints{0}) << "no cycle started";
  const robot::Reply unknown_model = cell.ask(request(Command::SelectModel, "nut"));
  EXPECT_EQ(unknown_model.status, Status::UnknownModel);
  EXPECT_EQ(unknown_model.integers, Ints{0}) << "the model still selected";
  EXPECT_EQ(cell.ask(request(Command::Ping)).integers, Ints{});
  EXPECT_EQ(cell.ask(request(Command::Status)).integers.size(), 3u);

  cell.service.handle(kRobot, request(Command::Trigger));
  const robot::Reply busy = cell.ask(request(Command::Trigger), 2);
  EXPECT_EQ(busy.status, Status::Busy);
  EXPECT_EQ(busy.integers, Ints{0});
  EXPECT_EQ(cell.collector.next(kRobot)->integers, Ints{1});
  for (const robot::Reply& pick : cell.allPicks()) EXPECT_EQ(pick.integers.size(), 3u);
  const robot::Reply no_more = cell.ask(request(Command::NextPick));
  EXPECT_EQ(no_more.status, Status::NoMorePicks);
  EXPECT_EQ(no_more.integers, (Ints{0, -1, -1}));
  // An object the cycle did not detect is a bad argument, and bad_message carries no integers.
  const robot::Reply unknown_object = cell.ask(request(Command::PickFailed, "999"));
  EXPECT_EQ(unknown_object.status, Status::BadMessage);
  EXPECT_EQ(unknown_object.integers, Ints{});
}

// A pick whose NEXT reply the robot's codec cannot encode (here a binary coordinate beyond the
// int32 range) would reach the robot as bad_message and be used up: the cell leaves it out, and
// the cycle's detail (and the log) names why. The settings check refuses such a scale at start;
// a far hand-eye pose or a reload can still produce such picks.
TEST(CellService, APickTheRobotCannotBeSentIsNeitherHandedOutNorLostSilently) {
  auto setup = std::make_shared<CellSetup>(*setupFor(cellConfigYaml(cellScene())));
  robot::CodecParams& codec = setup->config.robot.codec;
  codec.framing = robot::Framing::Binary;
  codec.position_scale = 1e7;  // 0.6 m = 6e9: beyond int32
  Cell cell(setup);
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  const robot::Reply next = cell.ask(request(Command::NextPick));
  EXPECT_EQ(next.status, Status::Unreachable);
  robot::ReplyDecoder decoder(codec);
  const std::string bytes = robot::encodeReply(next, codec);
  decoder.feed(bytes.data(), bytes.size());
  EXPECT_EQ(decoder.next()->status, next.status) << "the robot hears the reply as it was meant";
  const CellSnapshot snapshot = cell.service.snapshot();
  EXPECT_EQ(snapshot.last_picks, 0u);
  EXPECT_NE(snapshot.last_detail.find("robot.position_scale"), std::string::npos) << snapshot.last_detail;
}

// The cache only makes restarts fast: one that cannot be written costs the next start the model
// preparation, not this start.
TEST_F(CellServiceFiles, AModelCacheThatCannotBeWrittenStillStartsAndServes) {
  std::ofstream(pathOf("a_file")) << "not a directory";
  std::string yaml = cellConfigYaml(cellScene());
  const std::string cache = "cache: " + cellScene().directory + "/part.cache";
  ASSERT_NE(yaml.find(cache), std::string::npos);
  yaml.replace(yaml.find(cache), cache.size(), "cache: " + pathOf("a_file") + "/part.cache");
  Cell cell(yaml);
  EXPECT_FALSE(cell.setup->recipes[0].model_from_cache);
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::Ok);
}

// A cycle past its processing deadline stops computing: the cell is idle again soon after the
// timeout reply, instead of answering busy until the late stages return.
TEST(CellService, ACycleThatMissesItsProcessingDeadlineStopsComputing) {
  Cell cell(cellConfigYaml(cellScene(), "limits: {processing_timeout_ms: 1}\n"));
  ASSERT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok);
  EXPECT_EQ(cell.ask(request(Command::NextPick)).status, Status::Timeout);
  for (int polls = 0; cell.ask(request(Command::Status)).integers.at(0) != 0; ++polls) {
    ASSERT_LT(polls, 100000) << "the cell never became idle";
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const CellSnapshot stopped = cell.service.snapshot();
  EXPECT_EQ(stopped.last_status, Status::Timeout);
  EXPECT_EQ(stopped.last_parts_detected, 0u) << "the detection did not run to its end";
  EXPECT_NE(stopped.last_detail.find("stopped: cancelled"), std::string::npos) << stopped.last_detail;
  EXPECT_EQ(cell.ask(request(Command::Trigger)).status, Status::Ok) << "not busy";
}

// Stopping answers every robot waiting on the cycle, the TRIGGER and the NEXT alike.
TEST(CellService, StoppingAnswersEveryWaitingRobot) {
  Cell cell(cellConfigYaml(cellScene()), std::make_unique<SlowSource>(std::chrono::milliseconds(300)));
  cell.service.handle(kRobot, request(Command::Trigger));
  cell.service.handle(2, request(Command::NextPick));
  cell.service.stop();
  const auto trigger = cell.collector.next(kRobot, std::chrono::milliseconds(0));
  const auto next = cell.collector.next(2, std::chrono::milliseconds(0));
  ASSERT_TRUE(trigger && next);
  EXPECT_EQ(trigger->status, Status::InternalError);
  EXPECT_EQ(trigger->integers, std::vector<int32_t>{1});
  EXPECT_EQ(next->status, Status::InternalError);
  EXPECT_EQ(next->integers, (std::vector<int32_t>{0, -1, -1}));
}

}  // namespace
}  // namespace binpick::cell
