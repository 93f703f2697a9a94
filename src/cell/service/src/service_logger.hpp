#pragma once
// The service's spdlog logger, "cell".
#include "binpick/io/component_logger.hpp"

namespace binpick::cell {

inline std::shared_ptr<spdlog::logger> logger() { return componentLogger("cell"); }

}  // namespace binpick::cell
