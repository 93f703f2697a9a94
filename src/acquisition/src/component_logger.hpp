#pragma once
// Internal: the acquisition components' loggers ("sequencer", "replay", ...): see
// binpick/core/component_logger.hpp.
#include "binpick/core/component_logger.hpp"

namespace binpick::acquisition::detail {

using binpick::core::componentLogger;

}  // namespace binpick::acquisition::detail
