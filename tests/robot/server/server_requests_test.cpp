// Requests and replies: both framings, pipelining, deferred answers, many clients at once.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "running_server.hpp"

namespace binpick::test {
namespace {

using robot::Command;
using robot::Status;

TEST(ServerRequests, AsciiRequestGetsItsReply) {
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  client.sendBytes("PING\r\n");
  const robot::Reply reply = client.receiveReply();
  EXPECT_EQ(reply.command, Command::Ping);
  EXPECT_EQ(reply.status, Status::Ok);

  const robot::Reply model = client.roundTrip(request(Command::SelectModel, "3"));
  EXPECT_EQ(model.command, Command::SelectModel);
  EXPECT_EQ(model.integers, std::vector<int32_t>{3});
}

TEST(ServerRequests, BinaryRequestGetsItsReply) {
  robot::RobotServerParams params = loopbackParams();
  params.codec = binaryCodec();
  RunningServer running(params);
  TestClient client(running.port(), params.codec);
  const robot::Reply reply = client.roundTrip(request(Command::SelectModel, "7"));
  EXPECT_EQ(reply.command, Command::SelectModel);
  EXPECT_EQ(reply.status, Status::Ok);
  ASSERT_FALSE(reply.integers.empty());
  EXPECT_EQ(reply.integers[0], 7);
  EXPECT_EQ(client.roundTrip(request(Command::Status)).command, Command::Status);
}

TEST(ServerRequests, PipelinedRequestsAreAnsweredInOrder) {
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  std::string burst;
  for (int i = 0; i < 10; ++i) {
    burst += robot::encodeRequest(request(Command::SelectModel, std::to_string(i)), {});
  }
  client.sendBytes(burst);  // one write: the server sees them all at once
  for (int i = 0; i < 10; ++i) {
    const robot::Reply reply = client.receiveReply();
    ASSERT_EQ(reply.integers, std::vector<int32_t>{i}) << "reply " << i;
  }
}

TEST(ServerRequests, DeferredRepliesFromTheTestKeepTheirOrder) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  TestClient client(running.port());
  client.sendBytes("MODEL,1\r\nMODEL,2\r\n");
  auto [first_client, first] = running.handler().waitForRequest();
  EXPECT_EQ(first.argument, "1");
  // The second is handed over only after the first is answered, from this thread.
  EXPECT_EQ(running.handler().handledCount(), 1u);
  std::thread([&] { running.handler().answer(first_client, first); }).join();
  auto [second_client, second] = running.handler().waitForRequest();
  EXPECT_EQ(second_client, first_client);
  EXPECT_EQ(second.argument, "2");
  running.handler().answer(second_client, second);
  EXPECT_EQ(client.receiveReply().integers, std::vector<int32_t>{1});
  EXPECT_EQ(client.receiveReply().integers, std::vector<int32_t>{2});
  EXPECT_FALSE(running.handler().overlapped());
}

// Each client thread checks that every reply carries the number of its own request.
void runParallelClients(Answer answer) {
  RunningServer running(loopbackParams(), answer);
  constexpr int kClients = 8;
  constexpr int kRequests = 200;
  std::atomic<int> correct{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      try {
        TestClient client(running.port());
        for (int i = 0; i < kRequests; ++i) {
          const int tag = c * 1000 + i;
          const robot::Reply reply = client.roundTrip(request(Command::SelectModel, std::to_string(tag)));
          if (reply.integers == std::vector<int32_t>{tag}) ++correct;
        }
      } catch (const std::exception&) {
        // Counted as the missing correct replies.
      }
    });
  }
  for (std::thread& thread : clients) thread.join();
  EXPECT_EQ(correct.load(), kClients * kRequests);
  EXPECT_FALSE(running.handler().overlapped());
}

TEST(ServerRequests, EightParallelClientsAnsweredAtOnce) { runParallelClients(Answer::Immediately); }

TEST(ServerRequests, EightParallelClientsAnsweredFromAnotherThread) { runParallelClients(Answer::FromAnotherThread); }

TEST(ServerRequests, PipelinedRequestsReachTheHandlerOneAtATime) {
  RunningServer running(loopbackParams(), Answer::FromAnotherThread);
  TestClient client(running.port());
  std::string burst;
  for (int i = 0; i < 12; ++i) {
    burst += robot::encodeRequest(request(Command::SelectModel, std::to_string(i)), {});
  }
  client.sendBytes(burst);
  for (int i = 0; i < 12; ++i) ASSERT_EQ(client.receiveReply().integers, std::vector<int32_t>{i});
  EXPECT_FALSE(running.handler().overlapped());
}

// One codec at any moment: a reloaded codec reaches the robots already connected, from their
// next request on, so that every robot hears what the cell checked its picks against.
TEST(ServerRequests, ANewCodecReachesTheConnectedRobotsAtTheirNextRequest) {
  RunningServer running(loopbackParams());
  TestClient ascii(running.port());
  EXPECT_EQ(ascii.roundTrip(request(Command::Ping)).status, Status::Ok);
  TestClient binary(running.port(), binaryCodec());  // its robot program was changed first
  ASSERT_TRUE(running.waitForClientCount(2));
  EXPECT_EQ(running.server().setCodec(binaryCodec()), 2u);
  EXPECT_EQ(running.server().setCodec(binaryCodec()), 2u) << "the same codec again changes nothing";
  EXPECT_EQ(binary.roundTrip(request(Command::SelectModel, "5")).integers[0], 5);
  TestClient later(running.port(), binaryCodec());
  EXPECT_EQ(later.roundTrip(request(Command::SelectModel, "6")).integers[0], 6);
}

TEST(ServerRequests, HandlerThatThrowsIsAnsweredWithInternalError) {
  RunningServer running(loopbackParams());
  running.handler().throwOn(Command::Trigger);
  TestClient client(running.port());
  const robot::Reply failed = client.roundTrip(request(Command::Trigger));
  EXPECT_EQ(failed.command, Command::Trigger);
  EXPECT_EQ(failed.status, Status::InternalError);
  EXPECT_EQ(client.roundTrip(request(Command::Ping)).status, Status::Ok);
}

}  // namespace
}  // namespace binpick::test
