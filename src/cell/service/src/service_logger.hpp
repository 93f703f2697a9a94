#pragma once
// The service's spdlog logger, "cell" (created on first use; the daemon sets the format).
#include <spdlog/spdlog.h>

#include <memory>

namespace binpick::cell {

std::shared_ptr<spdlog::logger> logger();

}  // namespace binpick::cell
