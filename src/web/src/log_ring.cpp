#include "binpick/web/log_ring.hpp"

#include <algorithm>

#include "binpick/core/component_logger.hpp"

namespace binpick::web {

LogRing::LogRing(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {}

void LogRing::sink_it_(const spdlog::details::log_msg& message) {
  LogLine line;
  line.time = message.time;
  const auto level = spdlog::level::to_string_view(message.level);
  line.level.assign(level.data(), level.size());
  line.logger.assign(message.logger_name.data(), message.logger_name.size());
  line.text.assign(message.payload.data(), std::min(message.payload.size(), kMaxLogLineBytes));
  const std::lock_guard<std::mutex> lock(mutex_);
  lines_.push_back(std::move(line));
  while (lines_.size() > capacity_) lines_.pop_front();
}

std::vector<LogLine> LogRing::last(std::size_t count) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t n = std::min(count, lines_.size());
  return std::vector<LogLine>(lines_.end() - static_cast<std::ptrdiff_t>(n), lines_.end());
}

std::shared_ptr<LogRing> attachLogRing(std::size_t capacity) {
  auto ring = std::make_shared<LogRing>(capacity);
  core::addSinkToAllLoggers(ring);
  return ring;
}

}  // namespace binpick::web
