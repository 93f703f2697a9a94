#pragma once
// Internal: the "artefacts" logger, created on first use; safe when several threads or libraries
// race to create it.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>

namespace binpick::cell::artefacts_detail {

inline std::shared_ptr<spdlog::logger> artefactsLogger() {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = spdlog::get("artefacts")) return existing;
  try {
    return spdlog::stdout_color_mt("artefacts");
  } catch (const spdlog::spdlog_ex&) {
    // Registered elsewhere between our look-up and our creation: use that one.
    return spdlog::get("artefacts");
  }
}

}  // namespace binpick::cell::artefacts_detail
