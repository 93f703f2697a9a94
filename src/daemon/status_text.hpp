#pragma once
// The one line systemd shows for the service (systemctl status): state and the last cycle.
#include <string>

#include "binpick/cell/cell_service.hpp"

namespace binpick::daemon {

std::string statusText(const cell::CellSnapshot& snapshot, std::size_t clients);

}  // namespace binpick::daemon
