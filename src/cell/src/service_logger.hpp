#pragma once
// The service's spdlog logger, "cell".
#include "binpick/core/component_logger.hpp"

namespace binpick::cell {

inline std::shared_ptr<spdlog::logger> logger() { return core::componentLogger("cell"); }

}  // namespace binpick::cell
