#pragma once
// The spdlog logger of one component ("replay", "robot", "cell", ...), created on first use and
// writing to stderr, so that a cell's journal shows which part spoke while stdout stays the
// commands' own output. Header-only (links spdlog where it is used). Thread-safe: spdlog's
// registry refuses a second logger of one name, so look-up and creation happen under one lock,
// and a name registered by someone else in between is taken as it is.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace binpick::core {

namespace logger_detail {

struct Registry {
  std::mutex mutex;
  std::vector<spdlog::sink_ptr> extra_sinks;  // given to every logger (addSinkToAllLoggers)
};

inline Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace logger_detail

inline std::shared_ptr<spdlog::logger> componentLogger(const std::string& name) {
  logger_detail::Registry& registry = logger_detail::registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  if (auto existing = spdlog::get(name)) return existing;
  try {
    auto created = spdlog::stderr_color_mt(name);
    for (const spdlog::sink_ptr& sink : registry.extra_sinks) created->sinks().push_back(sink);
    return created;
  } catch (const spdlog::spdlog_ex&) {
    return spdlog::get(name);
  }
}

// Adds `sink` to every logger registered with spdlog (the default one included) and to every
// component logger created later: e.g. a server's own copy of the recent log lines. spdlog's
// loggers do not guard their sink lists, so call it before the threads that log start.
inline void addSinkToAllLoggers(const spdlog::sink_ptr& sink) {
  logger_detail::Registry& registry = logger_detail::registry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  registry.extra_sinks.push_back(sink);
  spdlog::apply_all([&](const std::shared_ptr<spdlog::logger>& logger) {
    auto& sinks = logger->sinks();
    if (std::find(sinks.begin(), sinks.end(), sink) == sinks.end()) sinks.push_back(sink);
  });
  // spdlog's default logger may be outside the registry (replaced without registering).
  auto& default_sinks = spdlog::default_logger_raw()->sinks();
  if (std::find(default_sinks.begin(), default_sinks.end(), sink) == default_sinks.end()) default_sinks.push_back(sink);
}

}  // namespace binpick::core
