#pragma once
// The thread count a params struct's `threads` field asks for. Pure: thread-safe.
#include <thread>

namespace binpick::core {

// `requested` > 0 as is; 0 means every hardware thread.
inline int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

}  // namespace binpick::core
