// Connections coming and going: allow-list, max_clients, clients leaving mid-request, stop(),
// stray replies, and no descriptor left behind.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "running_server.hpp"

namespace binpick::test {
namespace {

using robot::Command;
using robot::Status;

TEST(server_lifecycle, AllowListDecidesWhoIsServed) {
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

TEST(server_lifecycle, ConnectionsBeyondMaxClientsAreClosedAtOnce) {
  robot::RobotServerParams params = loopbackParams();
  params.max_clients = 2;
  RunningServer running(params);
  auto first = std::make_unique<TestClient>(running.port());
  TestClient second(running.port());
  EXPECT_EQ(first->roundTrip(request(Command::Ping)).status, Status::Ok);
  EXPECT_EQ(second.roundTrip(request(Command::Ping)).status, Status::Ok);
  TestClient third(running.port());
  EXPECT_TRUE(third.waitForClose());

  first.reset();
  ASSERT_TRUE(running.waitForClientCount(1));
  TestClient fourth(running.port());
  EXPECT_EQ(fourth.roundTrip(request(Command::Ping)).status, Status::Ok);
}

TEST(server_lifecycle, ClientLeavingWithARequestOutstanding) {
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

TEST(server_lifecycle, StrayRepliesAreDropped) {
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

TEST(server_lifecycle, StopClosesEveryClientEvenWithARequestOutstanding) {
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

TEST(server_lifecycle, StopBeforeRunMakesRunReturnAtOnce) {
  TestHandler handler(Answer::Immediately);
  robot::RobotServer server(loopbackParams(), handler);
  server.stop();
  server.run();
  server.run();  // a stopped server stays stopped
  SUCCEED();
}

TEST(server_lifecycle, NoDescriptorLeaksOverManyConnections) {
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
