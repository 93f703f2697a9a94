#pragma once
// Internal: how one client's bad requests reach the log. A robot program stuck in a loop sending
// garbage must not flood the journal: the first kBadRequestsLoggedInFull are logged one by one;
// later ones are counted, and the first counted one opens a window of `interval` that ends in one
// summary line (so at most one per interval). Used by the server thread only: not thread-safe.
#include <chrono>
#include <cstddef>
#include <optional>
#include <string>

#include "binpick/robot/protocol.hpp"
#include "binpick/robot/robot_server.hpp"

namespace binpick::robot::detail {

class BadRequestLog {
 public:
  using Clock = std::chrono::steady_clock;

  BadRequestLog(ClientId client, std::string peer, std::chrono::milliseconds interval);
  void record(const robot::Decoded& message, Clock::time_point now);
  // When the open window's summary is due; nothing while no bad request waits to be summarised.
  std::optional<Clock::time_point> summaryDue() const;
  // Logs the summary if its window has ended by `now`.
  void flushIfDue(Clock::time_point now);
  // Logs the summary of whatever was counted, window ended or not (the client is leaving).
  void flush(Clock::time_point now);

 private:
  ClientId client_;
  std::string peer_;
  std::chrono::milliseconds interval_;
  std::size_t logged_ = 0;      // logged one by one
  std::size_t suppressed_ = 0;  // counted in the open window
  Clock::time_point window_start_{};
  std::string latest_;  // the last counted one, for the summary
};

}  // namespace binpick::robot::detail
