// RobotServerParams::validate, setCodec/setAllowedClients refusals and binding errors name what
// was wrong.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "running_server.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

using Edit = std::function<void(robot::RobotServerParams&)>;

::testing::AssertionResult refusedNaming(const Edit& edit, const std::string& text) {
  robot::RobotServerParams params = loopbackParams();
  edit(params);
  return throwsNaming([&] { params.validate(); }, text);
}

TEST(ServerParams, DefaultsAreValid) {
  EXPECT_EQ(thrownMessage([] { robot::RobotServerParams().validate(); }), "");
}

TEST(ServerParams, ValidateNamesTheField) {
  using P = robot::RobotServerParams;
  EXPECT_TRUE(refusedNaming([](P& p) { p.bind_address = "localhost"; }, "robot_server.bind_address"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.port = 70000; }, "robot_server.port"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.port = -1; }, "robot_server.port"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.max_clients = 0; }, "robot_server.max_clients"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.max_queued_requests = 0; }, "robot_server.max_queued_requests"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.max_buffered_input = 40; }, "robot_server.max_buffered_input"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.max_buffered_output = 40; }, "robot_server.max_buffered_output"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.codec.position_decimals = -1; }, "position_decimals"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.idle_timeout_ms = -1; }, "robot_server.idle_timeout_ms"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.keepalive_idle_s = -1; }, "robot_server.keepalive_idle_s"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.keepalive_idle_s = 40000; }, "robot_server.keepalive_idle_s"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.keepalive_interval_s = 0; }, "robot_server.keepalive_interval_s"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.keepalive_count = 0; }, "robot_server.keepalive_count"));
  EXPECT_TRUE(refusedNaming([](P& p) { p.keepalive_count = 128; }, "robot_server.keepalive_count"));
  EXPECT_TRUE(
      refusedNaming([](P& p) { p.bad_request_log_interval_ms = 0; }, "robot_server.bad_request_log_interval_ms"));
  robot::RobotServerParams off = loopbackParams();
  off.idle_timeout_ms = 0;
  off.keepalive_idle_s = 0;
  EXPECT_EQ(thrownMessage([&] { off.validate(); }), "");
}

// Read from a settings file, the fields are named as that file's section spells them.
TEST(ServerParams, ValidateNamesTheOwnerItIsGiven) {
  robot::RobotServerParams params = loopbackParams();
  params.max_clients = 0;
  EXPECT_TRUE(throwsNaming([&] { params.validate("robot"); }, "robot.max_clients must be >= 1"));
  params = loopbackParams();
  params.allowed_clients = {"300.1.1.1"};
  EXPECT_TRUE(throwsNaming([&] { params.validate("robot"); }, "robot.allowed_clients entry \"300.1.1.1\""));
  params = loopbackParams();
  params.codec.max_line_length = 5000;  // named as itself, not as a buffer too small for it
  EXPECT_TRUE(throwsNaming([&] { params.validate("robot"); }, "robot.max_line_length"));
}

TEST(ServerParams, MalformedAllowListEntriesAreNamed) {
  for (const std::string entry :
       {"10.0.0.0/33", "10.0.0", "10.0.0.0/", "10.0.0.0/+8", "host.local", "10.0.0.256", ""}) {
    EXPECT_TRUE(refusedNaming([&](robot::RobotServerParams& p) { p.allowed_clients = {entry}; },
                              "robot_server.allowed_clients entry \"" + entry + "\""));
  }
  robot::RobotServerParams valid = loopbackParams();
  valid.allowed_clients = {"10.0.0.0/8", "192.168.1.7/24", "127.0.0.1"};  // host bits ignored
  EXPECT_EQ(thrownMessage([&] { valid.validate(); }), "");
}

TEST(ServerParams, ConstructorValidatesFirst) {
  robot::RobotServerParams params = loopbackParams();
  params.max_clients = 0;
  TestHandler handler(Answer::Never);
  EXPECT_TRUE(throwsNaming([&] { robot::RobotServer server(params, handler); }, "max_clients"));
}

TEST(ServerParams, RuntimeChangesAreCheckedAndRefusalsKeepTheOldSettings) {
  RunningServer running(loopbackParams());
  EXPECT_TRUE(throwsNaming([&] { running.server().setAllowedClients({"10.0.0.0/8", "nope"}); }, "\"nope\""));
  robot::CodecParams long_lines;
  long_lines.max_line_length = 10000;
  EXPECT_TRUE(throwsNaming([&] { running.server().setCodec(long_lines); }, "max_line_length"));
  TestClient client(running.port());
  EXPECT_EQ(client.roundTrip(request(robot::Command::Ping)).status, robot::Status::Ok);
}

TEST(ServerParams, BindingAnAddressInUseNamesAddressAndPort) {
  TestHandler handler(Answer::Never);
  robot::RobotServer first(loopbackParams(), handler);
  robot::RobotServerParams params = loopbackParams();
  params.port = first.port();
  const std::string message = thrownMessage([&] { robot::RobotServer second(params, handler); });
  EXPECT_NE(message.find("127.0.0.1:" + std::to_string(first.port())), std::string::npos) << message;
  EXPECT_NE(message.find("in use"), std::string::npos) << message;
}

}  // namespace
}  // namespace binpick::test
