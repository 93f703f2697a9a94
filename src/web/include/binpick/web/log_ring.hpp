#pragma once
// The recent log lines, for the web view: an spdlog sink keeping the last `capacity` lines in
// memory (core::addSinkToAllLoggers puts it beside the journal's). Thread-safe; a reader copies
// the lines under a lock held for that copy only.
#include <spdlog/details/null_mutex.h>
#include <spdlog/sinks/base_sink.h>

#include <chrono>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace binpick::web {

struct LogLine {
  std::chrono::system_clock::time_point time;
  std::string level;   // "info", "warning", ...
  std::string logger;  // the component: "cell", "robot", ...
  std::string text;    // at most kMaxLogLineBytes
};

constexpr std::size_t kMaxLogLineBytes = 1000;  // longer lines are cut (a path list, a dump)

// spdlog calls sink_it_ under the logger's own locking; the ring has its own mutex (the base's
// null mutex is not used), so that last() can read from any thread.
class LogRing : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
 public:
  explicit LogRing(std::size_t capacity = 200);
  // The newest `count` lines (fewer when the ring holds fewer), oldest first.
  std::vector<LogLine> last(std::size_t count) const;

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override;
  void flush_() override {}

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<LogLine> lines_;
};

// A ring fed by every logger of the process, those created later included
// (core::addSinkToAllLoggers). spdlog's sink lists are not guarded: call it before the threads
// that log start.
std::shared_ptr<LogRing> attachLogRing(std::size_t capacity = 200);

}  // namespace binpick::web
