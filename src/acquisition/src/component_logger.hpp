#pragma once
// Internal: the acquisition components' loggers ("sequencer", "replay", ...): see
// binpick/io/component_logger.hpp.
#include "binpick/io/component_logger.hpp"

namespace binpick::acquisition::detail {

using binpick::componentLogger;

}  // namespace binpick::acquisition::detail
