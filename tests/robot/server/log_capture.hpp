#pragma once
// The robot server's log lines (the "robot" logger, info and above) while one is in scope.
// Construct it before the RunningServer, so that it outlives the server thread: adding and
// removing the sink is safe only while nothing logs. Thread-safe reads.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace binpick::test {

// The server tests' default: warnings only (thousands of connection notices would bury the
// failures). Idempotent; RunningServer calls it.
void quietServerLogs();

class RobotLogCapture {
 public:
  RobotLogCapture();
  ~RobotLogCapture();
  RobotLogCapture(const RobotLogCapture&) = delete;
  RobotLogCapture& operator=(const RobotLogCapture&) = delete;

  std::vector<std::string> lines() const;  // the messages, oldest first
  std::size_t countContaining(const std::string& text) const;
  // Waits (a few seconds at most) until a line contains `text`.
  bool waitFor(const std::string& text) const;

 private:
  struct Sink;
  std::shared_ptr<Sink> sink_;
};

}  // namespace binpick::test
