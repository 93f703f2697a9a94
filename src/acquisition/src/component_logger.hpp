#pragma once
// Internal: the spdlog logger of one acquisition component ("sequencer", "replay", ...), created
// on first use. Loggers write to stderr so that a cell's log shows which part of the live path
// retried, reconnected or failed. Thread-safe.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>
#include <string>

namespace binpick::acquisition::detail {

inline std::shared_ptr<spdlog::logger> componentLogger(const std::string& name) {
  // spdlog's registry refuses a second logger of the same name: look up and create under one lock.
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = spdlog::get(name)) return existing;
  return spdlog::stderr_color_mt(name);
}

}  // namespace binpick::acquisition::detail
