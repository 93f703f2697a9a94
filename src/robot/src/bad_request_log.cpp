#include "bad_request_log.hpp"

#include <utility>

#include "binpick/core/component_logger.hpp"

namespace binpick::robot::detail {

BadRequestLog::BadRequestLog(ClientId client, std::string peer, std::chrono::milliseconds interval)
    : client_(client), peer_(std::move(peer)), interval_(interval) {}

void BadRequestLog::record(const robot::Decoded& message, Clock::time_point now) {
  const std::string what = std::string(robot::statusName(message.error)) + ": " + message.detail;
  if (logged_ < static_cast<std::size_t>(kBadRequestsLoggedInFull)) {
    ++logged_;
    core::componentLogger("robot")->info("client {} ({}): {}", client_, peer_, what);
    if (logged_ == static_cast<std::size_t>(kBadRequestsLoggedInFull)) {
      core::componentLogger("robot")->info("client {} ({}): further bad requests are counted, one summary per {} ms",
                                           client_, peer_, interval_.count());
    }
    return;
  }
  if (suppressed_ == 0) window_start_ = now;
  ++suppressed_;
  latest_ = what;
}

std::optional<BadRequestLog::Clock::time_point> BadRequestLog::summaryDue() const {
  if (suppressed_ == 0) return std::nullopt;
  return window_start_ + interval_;
}

void BadRequestLog::flushIfDue(Clock::time_point now) {
  const std::optional<Clock::time_point> due = summaryDue();
  if (due && now >= *due) flush(now);
}

void BadRequestLog::flush(Clock::time_point now) {
  if (suppressed_ == 0) return;
  const double seconds = std::chrono::duration<double>(now - window_start_).count();
  core::componentLogger("robot")->warn(
      "client {} ({}): {} more bad requests suppressed in the last {:.{}f} s (latest: {})", client_, peer_, suppressed_,
      seconds, seconds < 10.0 ? 1 : 0, latest_);
  suppressed_ = 0;
}

}  // namespace binpick::robot::detail
