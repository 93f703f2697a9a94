#include "status_text.hpp"

#include <sstream>

namespace binpick::daemon {
namespace {

const char* stateName(cell::CellState state) {
  switch (state) {
    case cell::CellState::Capturing: return "capturing";
    case cell::CellState::Computing: return "computing";
    default: return "idle";
  }
}

}  // namespace

std::string statusText(const cell::CellSnapshot& snapshot, std::size_t clients) {
  std::ostringstream text;
  text << stateName(snapshot.state) << ", recipe " << snapshot.recipe << ", " << clients << " robot(s)";
  if (snapshot.cycles_done > 0) {
    text << "; cycle " << snapshot.cycles_done << ": " << robot::statusName(snapshot.last_status) << ", "
         << snapshot.last_picks << " picks in " << static_cast<int>(snapshot.last_timing_ms.total) << " ms";
  }
  return text.str();
}

}  // namespace binpick::daemon
