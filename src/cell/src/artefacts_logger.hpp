#pragma once
// Internal: the "artefacts" logger, created on first use; safe when several threads or libraries
// race to create it.
#include <spdlog/spdlog.h>

#include "binpick/core/component_logger.hpp"

#include <memory>

namespace binpick::cell::artefacts_detail {

inline std::shared_ptr<spdlog::logger> artefactsLogger() { return core::componentLogger("artefacts"); }

}  // namespace binpick::cell::artefacts_detail
