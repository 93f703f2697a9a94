#include "service_logger.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <mutex>

namespace binpick::cell {

std::shared_ptr<spdlog::logger> logger() {
  static std::mutex creation;
  std::lock_guard lock(creation);
  if (auto existing = spdlog::get("cell")) return existing;
  return spdlog::stderr_color_mt("cell");
}

}  // namespace binpick::cell
