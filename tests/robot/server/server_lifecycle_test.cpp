// Connections coming and going: allow-list, max_clients and who makes room, the idle timeout and
// keepalive, clients leaving mid-request, stop(), stray replies, and no descriptor left behind.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "running_server.hpp"

namespace binpick::test {
namespace {

using robot::Command;
using robot::Status;

TEST(ServerLifecycle, AllowListDecidesWhoIsServed) {
  robot::RobotServerParams params = loopbackParams();
  params.allowed_clients = {"10.0.0.0/8"};
  RunningServer running(params);
  TestClient refused(running.port());
  EXPECT_TRUE(refused.waitForClose());

  // Entries that take or refuse 127.0.0.1, set while the server runs.
  const std::vector<std::pair<std::vector<std::string>, bool>> cases = {
      {{"127.0.0.1"}, true},
      {{"127.0.0.0/8"}, true},
      {{"0.0.0.0/0"}, true},
      {{"127.0.0.0/31"}, true},
      {{"127.0.0.2/31"}, false},
      {{"127.0.0.2"}, false},
      {{"10.0.0.0/8", "127.0.0.1"}, true},
      {{}, true},
  };
  for (const auto& [allowed, served] : cases) {
    running.server().setAllowedClients(allowed);
    TestClient client(running.port());
    if (served) {
      EXPECT_EQ(client.roundTrip(request(Command::Ping)).status, Status::Ok) << allowed.size();
    } else {
      EXPECT_TRUE(client.waitForClose()) << allowed[0];
    }
  }
  EXPECT_EQ(running.handler().handledCount(), 6u);
}

TEST(ServerLifecycle, ANewcomerBeyondMaxClientsReplacesTheLongestIdleClient) {
  robot::RobotServerParams params = loopbackParams();
  params.max_clients = 2;
  RunningServer running(params);
  TestClient first(running.port());
  TestClient second(running.port());
  EXPECT_EQ(first.roundTrip(request(Command::Ping)).status, Status::Ok);
  EXPECT_EQ(second.roundTrip(request(Command::Ping)).status, Status::Ok);

  TestClient third(running.port());
  EXPECT_EQ(third.roundTrip(request(Command::Ping)).status, Status::Ok);
  EXPECT_TRUE(first.waitForClose());  // its reply came first: idle longest
  EXPECT_EQ(second.roundTrip(request(Command::Ping)).status, Status::Ok);
  EXPECT_EQ(running.handler().disconnectedClients().size(), 1u);
}

// Eight connections that never say anything, or controllers that were switched off without
// closing, must not lock the robot out.
TEST(ServerLifecycle, SilentConnectionsFillingMaxClientsDoNotLockRobotsOut) {
  RunningServer running(loopbackParams());  // max_clients 8, no allow-list
  std::vector<std::unique_ptr<TestClient>> silent;
  for (int i = 0; i < robot::RobotServerParams().max_clients; ++i) {
    silent.push_back(std::make_unique<TestClient>(running.port()));
  }
  ASSERT_TRUE(running.waitForClientCount(silent.size()));
  // A robot rebooting over and over, never closing its old connections.
  std::vector<std::unique_ptr<TestClient>> reboots;
  for (int boot = 0; boot < 12; ++boot) {
    reboots.push_back(std::make_unique<TestClient>(running.port()));
    ASSERT_NO_THROW(EXPECT_EQ(reboots.back()->roundTrip(request(Command::Ping)).status, Status::Ok)) << boot;
  }
  for (const auto& connection : silent) EXPECT_TRUE(connection->waitForClose());
  EXPECT_EQ(running.server().clientCount(), 8u);
}

TEST(ServerLifecycle, ClientsWaitingForAReplyKeepTheirSlots) {
  robot::RobotServerParams params = loopbackParams();
  params.max_clients = 2;
  RunningServer running(params, Answer::ByTheTest);
  TestClient waiting(running.port());
  waiting.send(request(Command::Trigger));
  const auto [waiting_id, trigger] = running.handler().waitForRequest();
  TestClient idle(running.port());
  ASSERT_TRUE(running.waitForClientCount(2));

  // The idle one makes room, although the waiting one connected earlier.
  TestClient newcomer(running.port());
  EXPECT_TRUE(idle.waitForClose());
  newcomer.send(request(Command::Ping));
  const auto [newcomer_id, ping] = running.handler().waitForRequest();
  ASSERT_TRUE(running.waitForClientCount(2));

  // Both have a request with the handler now: a further connection is refused.
  TestClient refused(running.port());
  EXPECT_TRUE(refused.waitForClose());
  running.handler().answer(waiting_id, trigger);
  running.handler().answer(newcomer_id, ping);
  EXPECT_EQ(waiting.receiveReply().command, Command::Trigger);
  EXPECT_EQ(newcomer.receiveReply().command, Command::Ping);
}

TEST(ServerLifecycle, IdleClientsAreDisconnectedAfterIdleTimeout) {
  robot::RobotServerParams params = loopbackParams();
  params.idle_timeout_ms = 300;
  RunningServer running(params, Answer::ByTheTest);
  TestClient silent(running.port());
  EXPECT_TRUE(silent.waitForClose());

  // A request with the handler longer than the timeout does not count as idle, and the timeout
  // starts again with the reply.
  TestClient waiting(running.port());
  waiting.send(request(Command::Trigger));
  const auto [id, trigger] = running.handler().waitForRequest();
  std::this_thread::sleep_for(std::chrono::milliseconds(3 * params.idle_timeout_ms));
  running.handler().answer(id, trigger);
  EXPECT_EQ(waiting.receiveReply().command, Command::Trigger);
  EXPECT_TRUE(waiting.waitForClose());
  ASSERT_TRUE(running.handler().waitForDisconnects(2));
  EXPECT_EQ(running.server().clientCount(), 0u);
}

TEST(ServerLifecycle, ClientsTalkingWithinTheIdleTimeoutStay) {
  robot::RobotServerParams params = loopbackParams();
  params.idle_timeout_ms = 2000;
  RunningServer running(params);
  TestClient robot(running.port());
  // Longer than the timeout in all, each pause far shorter.
  for (int i = 0; i < 12; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(params.idle_timeout_ms / 8));
    ASSERT_EQ(robot.roundTrip(request(Command::Ping)).status, Status::Ok) << i;
  }
  EXPECT_TRUE(running.handler().disconnectedClients().empty());
}

// A dead peer is noticed by TCP keepalive: the options are set on the server's end.
TEST(ServerLifecycle, ClientSocketsUseTcpKeepalive) {
  const robot::RobotServerParams defaults;
  EXPECT_LE(defaults.keepalive_idle_s + defaults.keepalive_interval_s * defaults.keepalive_count, 60);
  robot::RobotServerParams params = loopbackParams();
  params.keepalive_idle_s = 7;
  params.keepalive_interval_s = 3;
  params.keepalive_count = 4;
  RunningServer running(params);
  TestClient client(running.port());
  EXPECT_EQ(client.roundTrip(request(Command::Ping)).status, Status::Ok);
  const int fd = serverSideSocket(running.port(), client.localPort());
  ASSERT_GE(fd, 0);
  auto option = [fd](int level, int name) {
    int value = -1;
    socklen_t length = sizeof value;
    ::getsockopt(fd, level, name, &value, &length);
    return value;
  };
  EXPECT_EQ(option(SOL_SOCKET, SO_KEEPALIVE), 1);
  EXPECT_EQ(option(IPPROTO_TCP, TCP_KEEPIDLE), 7);
  EXPECT_EQ(option(IPPROTO_TCP, TCP_KEEPINTVL), 3);
  EXPECT_EQ(option(IPPROTO_TCP, TCP_KEEPCNT), 4);

  params.keepalive_idle_s = 0;  // off
  RunningServer without(params);
  TestClient other(without.port());
  EXPECT_EQ(other.roundTrip(request(Command::Ping)).status, Status::Ok);
  const int other_fd = serverSideSocket(without.port(), other.localPort());
  ASSERT_GE(other_fd, 0);
  int keepalive = -1;
  socklen_t length = sizeof keepalive;
  ::getsockopt(other_fd, SOL_SOCKET, SO_KEEPALIVE, &keepalive, &length);
  EXPECT_EQ(keepalive, 0);
}

TEST(ServerLifecycle, ClientLeavingWithARequestOutstanding) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  auto client = std::make_unique<TestClient>(running.port());
  client->send(request(Command::Trigger));
  auto [id, trigger] = running.handler().waitForRequest();
  client.reset();
  ASSERT_TRUE(running.handler().waitForDisconnects(1));
  EXPECT_EQ(running.handler().disconnectedClients(), std::vector<robot::ClientId>{id});
  running.handler().answer(id, trigger);  // too late: dropped

  TestClient next(running.port());
  next.send(request(Command::Ping));
  auto [next_id, ping] = running.handler().waitForRequest();
  EXPECT_NE(next_id, id);  // ids are never reused
  running.handler().answer(next_id, ping);
  EXPECT_EQ(next.receiveReply().command, Command::Ping);
}

TEST(ServerLifecycle, StrayRepliesAreDropped) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  TestClient client(running.port());
  client.send(request(Command::SelectModel, "1"));
  auto [id, model] = running.handler().waitForRequest();
  running.server().reply(id + 1000, replyTo(model));  // no such client
  running.handler().answer(id, model);
  running.handler().answer(id, model);  // answered twice: the second has no request
  EXPECT_EQ(client.receiveReply().integers, std::vector<int32_t>{1});

  client.send(request(Command::Ping));
  auto [ping_id, ping] = running.handler().waitForRequest();
  running.handler().answer(ping_id, ping);
  EXPECT_EQ(client.receiveReply().command, Command::Ping) << "the duplicate reply was sent";
}

TEST(ServerLifecycle, StopClosesEveryClientEvenWithARequestOutstanding) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  TestClient waiting(running.port());
  TestClient idle(running.port());
  TestClient another(running.port());
  waiting.send(request(Command::Trigger));
  running.handler().waitForRequest();
  ASSERT_TRUE(running.waitForClientCount(3));

  running.stopAndJoin();
  EXPECT_TRUE(waiting.waitForClose());
  EXPECT_TRUE(idle.waitForClose());
  EXPECT_TRUE(another.waitForClose());
  EXPECT_EQ(running.handler().disconnectedClients().size(), 3u);
  EXPECT_EQ(running.server().clientCount(), 0u);
}

// A service stopping answers its waiting robots (internal_error) and then stops the server at
// once: those replies still reach the robots before their connections close.
TEST(ServerLifecycle, RepliesGivenJustBeforeStopAreSentBeforeTheClose) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  TestClient waiting(running.port());
  waiting.send(request(Command::NextPick));
  auto [id, next] = running.handler().waitForRequest();
  robot::Reply failed = replyTo(next);
  failed.status = robot::Status::InternalError;
  running.server().reply(id, failed);
  running.stopAndJoin();
  const robot::Reply received = waiting.receiveReply();
  EXPECT_EQ(received.command, Command::NextPick);
  EXPECT_EQ(received.status, robot::Status::InternalError);
  EXPECT_TRUE(waiting.waitForClose());
}

TEST(ServerLifecycle, StopBeforeRunMakesRunReturnAtOnce) {
  TestHandler handler(Answer::Immediately);
  robot::RobotServer server(loopbackParams(), handler);
  server.stop();
  server.run();
  server.run();  // a stopped server stays stopped
  SUCCEED();
}

TEST(ServerLifecycle, NoDescriptorLeaksOverManyConnections) {
  RunningServer running(loopbackParams());
  {
    // Warm up: the first connection creates the logger and whatever else lives for good.
    TestClient client(running.port());
    client.roundTrip(request(Command::Ping));
  }
  ASSERT_TRUE(running.waitForClientCount(0));
  const std::size_t before = openDescriptorCount();
  constexpr int kCycles = 2000;
  for (int i = 0; i < kCycles; ++i) {
    TestClient client(running.port());
    if (i % 3 == 1) client.roundTrip(request(Command::Ping));
    if (i % 3 == 2) client.send(request(Command::SelectModel, "1"));  // left unread
  }
  ASSERT_TRUE(running.waitForClientCount(0));
  ASSERT_TRUE(running.handler().waitForDisconnects(kCycles + 1));
  EXPECT_EQ(openDescriptorCount(), before);
}

}  // namespace
}  // namespace binpick::test
