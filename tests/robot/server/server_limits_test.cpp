// What a misbehaving client gets: error replies for garbage, a disconnect for breaking a limit,
// and never a stalled server for the others.
#include <gtest/gtest.h>

#include <atomic>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "running_server.hpp"

namespace binpick::test {
namespace {

using robot::Command;
using robot::Status;

TEST(ServerLimits, GarbageGetsErrorRepliesInOrderAndTheConnectionSurvives) {
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  client.sendBytes("HELLO\r\n");
  client.sendBytes(std::string(300, 'X') + "\r\n");  // oversized line
  client.sendBytes(std::string("PI\0NG\r\n", 7));    // a control character
  client.sendBytes("MODEL,1,2\r\n");                 // one argument too many
  client.sendBytes("PING\r\n");
  EXPECT_EQ(client.receiveReply().status, Status::UnknownCommand);
  EXPECT_EQ(client.receiveReply().status, Status::BadMessage);
  EXPECT_EQ(client.receiveReply().status, Status::BadMessage);
  const robot::Reply bad_argument = client.receiveReply();
  EXPECT_EQ(bad_argument.status, Status::BadMessage);
  EXPECT_EQ(bad_argument.command, Command::SelectModel);
  const robot::Reply ping = client.receiveReply();
  EXPECT_EQ(ping.command, Command::Ping);
  EXPECT_EQ(ping.status, Status::Ok);
}

// A robot matching replies to its requests must never read a reply naming a command it did not
// send: a line without a readable keyword is answered "ERROR,8".
TEST(ServerLimits, UnreadableLinesAreAnsweredWithErrorNeverAnotherCommand) {
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {",,,", "ERROR"},
      {std::string("NEXT\0", 5), "NEXT"},  // a NEXT, garbled: its own keyword
      {"TRIGGER\xff", "TRIGGER"},
      {"\x01\x02", "ERROR"},
      {std::string("NE\0XT", 5), "ERROR"},
      {std::string(100, 'A'), "ERROR"},  // longer than max_line_length
      {"NEXT," + std::string(100, 'A'), "NEXT"},
  };
  for (const auto& [line, keyword] : cases) {
    client.sendBytes(line + "\r\n");
    const robot::Reply reply = client.receiveReply();
    EXPECT_EQ(std::string(robot::commandKeyword(reply.command)), keyword) << line;
    EXPECT_EQ(reply.status, Status::BadMessage) << line;
  }
  EXPECT_EQ(client.roundTrip(request(Command::Ping)).status, Status::Ok);
}

// A program stuck sending garbage must not flood the journal: a few lines, then summaries.
TEST(ServerLimits, BadRequestsOfAClientAreLoggedRateLimited) {
  const RobotLogCapture log;
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  std::string garbage;
  for (int i = 0; i < 100; ++i) garbage += "HELLO" + std::to_string(i) + "\r\n";
  client.sendBytes(garbage);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(client.receiveReply().status, Status::UnknownCommand);
  EXPECT_EQ(client.roundTrip(request(Command::Ping)).status, Status::Ok);
  EXPECT_EQ(log.countContaining("unknown command 'HELLO"), static_cast<std::size_t>(robot::kBadRequestsLoggedInFull));
  // What was not logged is told when the client leaves.
  client.close();
  ASSERT_TRUE(running.handler().waitForDisconnects(1));
  EXPECT_EQ(log.countContaining("95 more bad requests suppressed"), 1u);
}

TEST(ServerLimits, BadRequestSummariesComeOncePerInterval) {
  const RobotLogCapture log;
  robot::RobotServerParams params = loopbackParams();
  params.bad_request_log_interval_ms = 200;
  RunningServer running(params);
  TestClient client(running.port());
  for (int burst : {20, 3}) {
    for (int i = 0; i < burst; ++i) client.sendBytes(",,,\r\n");
    for (int i = 0; i < burst; ++i) ASSERT_EQ(client.receiveReply().status, Status::BadMessage);
    // Nothing more arrives: the summary comes when the interval ends, not with the next request.
    const std::string summary =
        std::to_string(burst == 20 ? burst - robot::kBadRequestsLoggedInFull : burst) + " more bad requests suppressed";
    EXPECT_TRUE(log.waitFor(summary)) << summary;
  }
  EXPECT_EQ(log.countContaining("no keyword"), static_cast<std::size_t>(robot::kBadRequestsLoggedInFull) + 2);
  EXPECT_EQ(log.countContaining("suppressed"), 2u);
}

TEST(ServerLimits, ErrorRepliesWaitBehindTheRequestWithTheHandler) {
  RunningServer running(loopbackParams(), Answer::ByTheTest);
  TestClient client(running.port());
  client.sendBytes("MODEL,4\r\nBOGUS\r\n");
  auto [id, model] = running.handler().waitForRequest();
  running.handler().answer(id, model);
  const robot::Reply first = client.receiveReply();
  EXPECT_EQ(first.command, Command::SelectModel);
  EXPECT_EQ(first.integers, std::vector<int32_t>{4});
  EXPECT_EQ(client.receiveReply().status, Status::UnknownCommand);
}

TEST(ServerLimits, SeededRandomAsciiGarbageNeverCostsTheConnection) {
  RunningServer running(loopbackParams());
  TestClient client(running.port());
  std::mt19937 random(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(1, 120);
  for (int round = 0; round < 50; ++round) {
    std::string garbage;
    const int size = length(random);
    for (int i = 0; i < size; ++i) garbage += static_cast<char>(byte(random));
    // The blank line ends whatever the garbage left open; the PING tells where its replies end.
    client.sendBytes(garbage + "\r\n\r\nPING\r\n");
    while (true) {
      const robot::Reply reply = client.receiveReply();
      if (reply.command == Command::Ping && reply.status == Status::Ok) break;
    }
  }
}

TEST(ServerLimits, SeededRandomBinaryGarbageGetsOneReplyPerMessage) {
  robot::RobotServerParams params = loopbackParams();
  params.codec = binaryCodec();
  RunningServer running(params);
  TestClient client(running.port(), params.codec);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> byte(0, 255);
  int errors = 0;
  for (int round = 0; round < 20; ++round) {
    std::string garbage;
    for (std::size_t i = 0; i < 8 * robot::kBinaryRequestSize; ++i) {
      garbage += static_cast<char>(byte(random));
    }
    client.sendBytes(garbage);
    for (int i = 0; i < 8; ++i) errors += client.receiveReply().status != Status::Ok ? 1 : 0;
    ASSERT_EQ(client.roundTrip(request(Command::SelectModel, "9")).integers[0], 9);
  }
  EXPECT_GT(errors, 100);  // random ids are almost never a command
}

TEST(ServerLimits, ClientPipeliningBeyondTheQueueLimitIsDisconnected) {
  robot::RobotServerParams params = loopbackParams();
  params.max_queued_requests = 4;
  RunningServer running(params, Answer::ByTheTest);
  std::string four;
  for (int i = 0; i < 4; ++i) four += "MODEL," + std::to_string(i) + "\r\n";

  TestClient within(running.port());
  within.sendBytes(four);
  for (int i = 0; i < 4; ++i) {
    auto [id, model] = running.handler().waitForRequest();
    running.handler().answer(id, model);
    EXPECT_EQ(within.receiveReply().integers, std::vector<int32_t>{i});
  }

  TestClient beyond(running.port());
  beyond.sendBytes(four + "MODEL,4\r\n");
  EXPECT_TRUE(beyond.waitForClose());
  ASSERT_TRUE(running.handler().waitForDisconnects(1));
  // Its first request reached the handler before the rest broke the limit.
  EXPECT_EQ(running.handler().waitForRequest().first, running.handler().disconnectedClients()[0]);
  within.send(request(Command::Ping));
  auto [id, ping] = running.handler().waitForRequest();
  running.handler().answer(id, ping);
  EXPECT_EQ(within.receiveReply().command, Command::Ping);
}

TEST(ServerLimits, ClientThatDoesNotReadIsDisconnectedWhileAnotherIsServed) {
  robot::RobotServerParams params = loopbackParams();
  params.codec = binaryCodec();
  params.max_buffered_output = 4096;
  RunningServer running(params);
  TestClient reader(running.port(), params.codec);
  EXPECT_EQ(reader.roundTrip(request(Command::Ping)).status, Status::Ok);

  std::atomic<bool> flooding{true};
  std::atomic<int> served{0};
  std::thread reading([&] {
    for (int i = 0; flooding.load() || i < 50; ++i) {
      try {
        if (reader.roundTrip(request(Command::SelectModel, std::to_string(i))).integers[0] == i) {
          ++served;
        }
      } catch (const std::exception&) {
        return;
      }
    }
  });
  TestClient flooder(running.port(), params.codec, 4096);
  std::string burst;
  for (int i = 0; i < 16; ++i) burst += robot::encodeRequest(request(Command::Ping), params.codec);
  bool dropped = false;
  // Far more replies than the kernel buffers hold: the server must give up on this client.
  for (int i = 0; i < 100000 && !dropped; ++i) dropped = !flooder.trySendBytes(burst);
  flooding.store(false);
  reading.join();
  EXPECT_TRUE(dropped);
  EXPECT_TRUE(running.handler().waitForDisconnects(1));
  EXPECT_GE(served.load(), 50);
  EXPECT_EQ(reader.roundTrip(request(Command::Ping)).status, Status::Ok);
}

}  // namespace
}  // namespace binpick::test
