#pragma once
// Internal: the "robot" logger of the server, created on first use. It writes to stderr so that
// a cell's log shows which controller connected, was refused or was dropped. Thread-safe.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>

namespace binpick::cell::detail {

inline std::shared_ptr<spdlog::logger> serverLogger() {
  // spdlog's registry refuses a second logger of the same name: look up and create under one
  // lock. Another library may still register the name between our get() and create: take theirs.
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = spdlog::get("robot")) return existing;
  try {
    return spdlog::stderr_color_mt("robot");
  } catch (const spdlog::spdlog_ex&) {
    return spdlog::get("robot");
  }
}

}  // namespace binpick::cell::detail
