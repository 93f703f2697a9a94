// Backoff: doubling waits between attempts that keep failing.
#include "backoff.hpp"

#include <algorithm>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::acquisition {

Backoff::Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds max) : initial_(initial), max_(max) {
  if (initial.count() <= 0 || max < initial) {
    throw core::Error("backoff: needs 0 < initial <= max (got " + std::to_string(initial.count()) + " ms and " +
                      std::to_string(max.count()) + " ms)");
  }
}

void Backoff::failed(Clock::time_point now) {
  ++failures_;
  last_failure_ = now;
}

void Backoff::succeeded() { failures_ = 0; }

std::chrono::milliseconds Backoff::delay() const {
  if (failures_ == 0) return std::chrono::milliseconds(0);
  std::chrono::milliseconds delay = initial_;
  // Doubling stops at max: no overflow however long the camera stays away.
  for (int i = 1; i < failures_ && delay < max_; ++i) delay *= 2;
  return std::min(delay, max_);
}

Backoff::Clock::duration Backoff::wait(Clock::time_point now) const {
  const Clock::time_point next_attempt = last_failure_ + delay();
  return failures_ == 0 || now >= next_attempt ? Clock::duration::zero() : next_attempt - now;
}

}  // namespace binpick::acquisition
