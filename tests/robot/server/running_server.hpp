#pragma once
// A robot server on loopback, running in its own thread for the length of a test, with a
// TestHandler; what the server tests include.
#include <cstddef>
#include <future>
#include <memory>
#include <thread>

#include "binpick/robot/robot_server.hpp"
#include "log_capture.hpp"
#include "test_client.hpp"
#include "test_handler.hpp"

namespace binpick::test {

// Loopback, any free port.
robot::RobotServerParams loopbackParams();

class RunningServer {
 public:
  explicit RunningServer(const robot::RobotServerParams& params, Answer answer = Answer::Immediately);
  ~RunningServer();
  robot::RobotServer& server() { return *server_; }
  TestHandler& handler() { return handler_; }
  int port() const { return server_->port(); }
  // Fails the test (and aborts rather than hang) when run() does not return.
  void stopAndJoin();
  bool waitForClientCount(std::size_t count);

 private:
  TestHandler handler_;
  std::unique_ptr<robot::RobotServer> server_;
  std::future<void> finished_;
  std::thread thread_;
  bool joined_ = false;
};

}  // namespace binpick::test
