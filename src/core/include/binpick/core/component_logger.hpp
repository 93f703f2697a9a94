#pragma once
// The spdlog logger of one component ("replay", "robot", "cell", ...), created on first use and
// writing to stderr, so that a cell's journal shows which part spoke while stdout stays the
// commands' own output. Header-only (links spdlog where it is used). Thread-safe: spdlog's
// registry refuses a second logger of one name, so look-up and creation happen under one lock,
// and a name registered by someone else in between is taken as it is.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>
#include <string>

namespace binpick::core {

inline std::shared_ptr<spdlog::logger> componentLogger(const std::string& name) {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = spdlog::get(name)) return existing;
  try {
    return spdlog::stderr_color_mt(name);
  } catch (const spdlog::spdlog_ex&) {
    return spdlog::get(name);
  }
}

}  // namespace binpick::core
