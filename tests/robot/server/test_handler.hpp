#pragma once
// The request handler of the server tests: it answers at once, from a thread of its own, when
// the test says so, or never, and records what it saw. Thread-safe.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "binpick/robot/protocol.hpp"
#include "binpick/robot/robot_server.hpp"

namespace binpick::test {

using robot::ClientId;

enum class Answer { Immediately, FromAnotherThread, ByTheTest, Never };

// The reply every test handler gives: the command echoed, Ok, and the argument when it is a
// number as the only integer (so that a reply shows which request it answers).
robot::Reply replyTo(const robot::Request& request);

class TestHandler : public robot::RequestHandler {
 public:
  explicit TestHandler(Answer answer) : answer_(answer) {}
  ~TestHandler() override { stopAnswering(); }
  void attach(robot::RobotServer& server);
  void stopAnswering();
  void throwOn(robot::Command command) { throw_on_ = command; }

  void handle(robot::ClientId client, const robot::Request& request) override;
  void disconnected(robot::ClientId client) override;

  // Answer::ByTheTest: the next request handed over; throws after a few seconds without one.
  std::pair<robot::ClientId, robot::Request> waitForRequest();
  void answer(robot::ClientId client, const robot::Request& request);
  bool waitForDisconnects(std::size_t count);
  std::vector<robot::ClientId> disconnectedClients();
  std::size_t handledCount();
  // A request was handed over while the same client's previous one was unanswered.
  bool overlapped();

 private:
  void answerInTurn();

  Answer answer_;
  std::optional<robot::Command> throw_on_;
  robot::RobotServer* server_ = nullptr;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<robot::ClientId, robot::Request>> waiting_;
  std::set<robot::ClientId> outstanding_;
  std::vector<robot::ClientId> disconnected_;
  std::size_t handled_ = 0;
  bool overlapped_ = false;
  bool stopping_ = false;
  std::thread answerer_;
};

}  // namespace binpick::test
