#include "log_capture.hpp"

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

#include "binpick/core/component_logger.hpp"

namespace binpick::test {
namespace {

constexpr std::size_t kKeptLines = 10000;
constexpr auto kPatience = std::chrono::seconds(10);

std::shared_ptr<spdlog::logger> robotLogger() { return core::componentLogger("robot"); }

}  // namespace

struct RobotLogCapture::Sink {
  std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> ring =
      std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(kKeptLines);
};

void quietServerLogs() {
  static std::once_flag once;
  std::call_once(once, [] { spdlog::set_level(spdlog::level::warn); });
}

RobotLogCapture::RobotLogCapture() : sink_(std::make_shared<Sink>()) {
  quietServerLogs();
  sink_->ring->set_pattern("%v");
  const auto logger = robotLogger();
  logger->sinks().push_back(sink_->ring);
  logger->set_level(spdlog::level::info);
}

RobotLogCapture::~RobotLogCapture() {
  const auto logger = robotLogger();
  auto& sinks = logger->sinks();
  sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_->ring), sinks.end());
  logger->set_level(spdlog::level::warn);
}

std::vector<std::string> RobotLogCapture::lines() const { return sink_->ring->last_formatted(); }

std::size_t RobotLogCapture::countContaining(const std::string& text) const {
  const std::vector<std::string> all = lines();
  return static_cast<std::size_t>(std::count_if(
      all.begin(), all.end(), [&](const std::string& line) { return line.find(text) != std::string::npos; }));
}

bool RobotLogCapture::waitFor(const std::string& text) const {
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (countContaining(text) == 0) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace binpick::test
