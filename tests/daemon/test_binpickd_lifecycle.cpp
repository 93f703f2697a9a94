// binpickd as systemd runs it: readiness, watchdog, reload on SIGHUP and stop on SIGTERM in the
// middle of a cycle, and refusal of bad settings.
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "binpick/robot/protocol.hpp"
#include "daemon_fixture.hpp"

namespace binpick::cell::testing {
namespace {

using namespace std::chrono_literals;
using robot::Command;
using robot::Status;

TEST_F(DaemonTest, TellsSystemdItIsReadyAndFeedsTheWatchdog) {
  start("", 400000);  // WatchdogSec=0.4s: pings every 0.2 s
  EXPECT_TRUE(notify_->waitFor("READY=1", 60s));
  EXPECT_TRUE(notify_->waitFor("WATCHDOG=1", 10s));
  EXPECT_TRUE(notify_->waitFor("WATCHDOG=1", 10s));
  RobotClient robot(port_);
  EXPECT_EQ(robot.ask(request(Command::Ping)).status, Status::Ok);
  daemon_->signal(SIGTERM);
  EXPECT_TRUE(notify_->waitFor("STOPPING=1", 30s));
  EXPECT_EQ(daemon_->wait(60s), 0);
}

TEST_F(DaemonTest, ReloadsOnSighupDuringACycleWithoutDroppingTheRobot) {
  start();
  ASSERT_TRUE(notify_->waitFor("READY=1", 60s));
  RobotClient robot(port_);
  robot.sendRaw(robot::encodeRequest(request(Command::Trigger), {}));
  writeConfig("limits: {max_picks: 1}\n");
  daemon_->signal(SIGHUP);
  EXPECT_TRUE(notify_->waitFor("RELOADING=1", 30s));
  EXPECT_TRUE(notify_->waitFor("READY=1", 60s));
  const auto triggered = robot.receive(60s);
  ASSERT_TRUE(triggered.has_value()) << "the connection survived the reload";
  EXPECT_EQ(triggered->status, Status::Ok);

  // The next cycle runs with the reloaded settings: one pick at most.
  while (robot.ask(request(Command::NextPick)).status == Status::Ok) {
  }
  ASSERT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok);
  const robot::Reply only = robot.ask(request(Command::NextPick));
  EXPECT_EQ(only.status, Status::Ok);
  EXPECT_EQ(only.integers.at(0), 0) << "no pick remaining after the first";

  // A broken file is refused; the running settings stay and the robot is still served.
  std::ofstream(config_path_) << "robot: {port: [\n";
  daemon_->signal(SIGHUP);
  EXPECT_TRUE(notify_->waitFor("READY=1", 60s));
  EXPECT_EQ(robot.ask(request(Command::Ping)).status, Status::Ok);
  EXPECT_NE(daemonStderr().find("reload failed"), std::string::npos);
}

// A technician rewrites calib.yaml and the service is reloaded before the file is whole: the reload
// is refused as a whole, the cell keeps its calibration and picks on, and the next reload, with the
// file complete, is taken.
TEST_F(DaemonTest, AReloadThatWouldLoseTheCalibrationIsRefusedAndTheCellPicksOn) {
  const std::string calibration = pathOf("calib.yaml");
  std::filesystem::copy_file(cellScene().calibration, calibration);
  config_text_ = cellConfigYaml(cellScene());
  config_text_.replace(config_text_.find(cellScene().calibration), cellScene().calibration.size(), calibration);
  start();
  ASSERT_TRUE(notify_->waitFor("READY=1", 60s));
  RobotClient robot(port_);
  ASSERT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok);
  ASSERT_EQ(robot.ask(request(Command::NextPick)).status, Status::Ok);

  std::ofstream(calibration, std::ios::trunc) << "camera: {width: 12";  // half written
  daemon_->signal(SIGHUP);
  EXPECT_TRUE(notify_->waitFor("READY=1", 60s));
  EXPECT_NE(daemonStderr().find("would lose its rig calibration"), std::string::npos) << daemonStderr();
  ASSERT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok) << "the running calibration was kept";
  EXPECT_EQ(robot.ask(request(Command::NextPick)).status, Status::Ok);

  std::filesystem::copy_file(cellScene().calibration, calibration, std::filesystem::copy_options::overwrite_existing);
  daemon_->signal(SIGHUP);
  EXPECT_TRUE(notify_->waitFor("READY=1", 60s));
  EXPECT_NE(daemonStderr().find("reloaded"), std::string::npos);
  EXPECT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok);
}

TEST_F(DaemonTest, StopsCleanlyOnSigtermInTheMiddleOfACycle) {
  start();
  ASSERT_TRUE(notify_->waitFor("READY=1", 60s));
  RobotClient robot(port_);
  robot.sendRaw(robot::encodeRequest(request(Command::Trigger), {}));
  std::this_thread::sleep_for(20ms);  // let the cycle start
  daemon_->signal(SIGTERM);
  EXPECT_EQ(daemon_->wait(60s), 0) << daemonStderr();
  // The robot got its answer before the connection closed: the capture, or "stopping".
  const auto reply = robot.receive(1s);
  ASSERT_TRUE(reply.has_value()) << "the connection closed without a reply";
  EXPECT_TRUE(reply->status == Status::Ok || reply->status == Status::InternalError)
      << robot::statusName(reply->status);
}

// A robot whose NEXT waits for the cycle hears internal_error when the service stops, not a bare
// close. The recipe's detection is made slow (every scene point a reference, on one thread), so
// that the cycle is still computing when SIGTERM comes.
TEST_F(DaemonTest, ARobotWaitingForTheCycleHearsInternalErrorOnSigterm) {
  std::ofstream(pathOf("slow.yaml")) << "detection:\n"
                                        "  method: drost\n"
                                        "  threads: 1\n"
                                        "  voting: {reference_fraction: 1.0, referred_fraction: 1.0}\n";
  config_text_ = cellConfigYaml(cellScene());
  const std::string settings = std::string("settings: ") + BINPICK_CONFIG_DIR + "/virtual-cell.yaml";
  ASSERT_NE(config_text_.find(settings), std::string::npos);
  config_text_.replace(config_text_.find(settings), settings.size(), "settings: " + pathOf("slow.yaml"));
  start();
  ASSERT_TRUE(notify_->waitFor("READY=1", 60s));
  RobotClient robot(port_);
  ASSERT_EQ(robot.ask(request(Command::Trigger)).status, Status::Ok);  // the images are taken
  robot.sendRaw(robot::encodeRequest(request(Command::NextPick), {}));
  std::this_thread::sleep_for(100ms);  // let the NEXT reach the service
  daemon_->signal(SIGTERM);
  const auto reply = robot.receive(60s);
  ASSERT_TRUE(reply.has_value()) << "the connection closed without a reply";
  EXPECT_EQ(reply->command, Command::NextPick);
  EXPECT_EQ(reply->status, Status::InternalError);
  EXPECT_EQ(daemon_->wait(60s), 0) << daemonStderr();
}

TEST_F(DaemonTest, RefusesBadSettingsNamingTheKey) {
  config_path_ = pathOf("bad.yaml");
  std::ofstream(config_path_) << cellConfigYaml(cellScene(), "limits: {avoid_cycles: -2}\n");
  DaemonOptions options;
  options.config_path = config_path_;
  options.port_file = pathOf("port");
  options.stderr_file = pathOf("stderr");
  DaemonProcess daemon(options);
  EXPECT_EQ(daemon.wait(60s), 1);
  EXPECT_NE(daemonStderr().find("limits.avoid_cycles"), std::string::npos) << daemonStderr();
}

}  // namespace
}  // namespace binpick::cell::testing
