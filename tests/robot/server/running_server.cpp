#include "running_server.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <exception>

namespace binpick::test {
namespace {

// How long run() may take to return after stop(), and clients to come and go.
constexpr auto kPatience = std::chrono::seconds(10);

}  // namespace

robot::RobotServerParams loopbackParams() {
  robot::RobotServerParams params;
  params.bind_address = "127.0.0.1";
  params.port = 0;
  return params;
}

RunningServer::RunningServer(const robot::RobotServerParams& params, Answer answer) : handler_(answer) {
  quietServerLogs();
  server_ = std::make_unique<robot::RobotServer>(params, handler_);
  handler_.attach(*server_);
  std::promise<void> finished;
  finished_ = finished.get_future();
  thread_ = std::thread([this, promise = std::move(finished)]() mutable {
    try {
      server_->run();
      promise.set_value();
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  });
}

RunningServer::~RunningServer() {
  if (!joined_) stopAndJoin();
  handler_.stopAnswering();
}

void RunningServer::stopAndJoin() {
  joined_ = true;
  server_->stop();
  if (finished_.wait_for(kPatience) != std::future_status::ready) {
    ADD_FAILURE() << "run() did not return after stop()";
    std::abort();  // joining would hang the whole test run
  }
  thread_.join();
  try {
    finished_.get();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "run() threw: " << error.what();
  }
}

bool RunningServer::waitForClientCount(std::size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (server_->clientCount() != count) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace binpick::test
