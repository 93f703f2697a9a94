#include "test_handler.hpp"

#include <chrono>
#include <stdexcept>
#include <string>

namespace binpick::test {
namespace {

// How long a test waits for the server to hand over a request or report a disconnect.
constexpr auto kPatience = std::chrono::seconds(10);

}  // namespace

robot::Reply replyTo(const robot::Request& request) {
  robot::Reply reply;
  reply.command = request.command;
  if (request.argument) {
    try {
      reply.integers.push_back(std::stoi(*request.argument));
    } catch (const std::exception&) {
      // Not a number: no integer.
    }
  }
  return reply;
}

void TestHandler::attach(robot::RobotServer& server) {
  server_ = &server;
  if (answer_ == Answer::FromAnotherThread) answerer_ = std::thread([this] { answerInTurn(); });
}

void TestHandler::stopAnswering() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (answerer_.joinable()) answerer_.join();
}

void TestHandler::handle(robot::ClientId client, const robot::Request& request) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++handled_;
    if (!outstanding_.insert(client).second) overlapped_ = true;
    if (throw_on_ == request.command) {
      outstanding_.erase(client);
      throw std::runtime_error("the test handler refuses this command");
    }
    if (answer_ == Answer::FromAnotherThread || answer_ == Answer::ByTheTest) {
      waiting_.emplace_back(client, request);
    }
  }
  changed_.notify_all();
  if (answer_ == Answer::Immediately) answer(client, request);
}

void TestHandler::disconnected(robot::ClientId client) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    disconnected_.push_back(client);
    outstanding_.erase(client);
  }
  changed_.notify_all();
}

void TestHandler::answer(robot::ClientId client, const robot::Request& request) {
  {
    // Before reply(): the server may hand over the next request as soon as it has the reply.
    const std::lock_guard<std::mutex> lock(mutex_);
    outstanding_.erase(client);
  }
  server_->reply(client, replyTo(request));
}

void TestHandler::answerInTurn() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
    if (stopping_) return;
    const auto [client, request] = waiting_.front();
    waiting_.pop_front();
    lock.unlock();
    answer(client, request);
    lock.lock();
  }
}

std::pair<robot::ClientId, robot::Request> TestHandler::waitForRequest() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!changed_.wait_for(lock, kPatience, [this] { return !waiting_.empty(); })) {
    throw std::runtime_error("no request reached the handler");
  }
  auto front = waiting_.front();
  waiting_.pop_front();
  return front;
}

bool TestHandler::waitForDisconnects(std::size_t count) {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, kPatience, [&] { return disconnected_.size() >= count; });
}

std::vector<robot::ClientId> TestHandler::disconnectedClients() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return disconnected_;
}

std::size_t TestHandler::handledCount() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return handled_;
}

bool TestHandler::overlapped() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return overlapped_;
}

}  // namespace binpick::test
