#pragma once
// Internal: the "robot" logger of the server, created on first use. It writes to stderr so that
// a cell's log shows which controller connected, was refused or was dropped. Thread-safe.
#include <spdlog/spdlog.h>

#include "binpick/core/component_logger.hpp"

#include <memory>

namespace binpick::robot::detail {

inline std::shared_ptr<spdlog::logger> serverLogger() { return core::componentLogger("robot"); }

}  // namespace binpick::robot::detail
