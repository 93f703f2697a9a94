#pragma once
// How long to wait before trying again something that keeps failing (reopening a camera): the
// first wait is `initial`, doubling with each further failure up to `max`; a success starts over.
// The time is passed in, so the caller chooses the clock and tests need not sleep.
//
// Thread-safety: a value type; one Backoff is used from one thread.
#include <chrono>

namespace binpick::acquisition {

class Backoff {
 public:
  using Clock = std::chrono::steady_clock;
  // Throws core::Error unless 0 < initial <= max.
  Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds max);

  void failed(Clock::time_point now);
  void succeeded();
  int failures() const { return failures_; }
  // The wait after the failures so far: 0 with none, then initial, 2 initial, ... up to max.
  std::chrono::milliseconds delay() const;
  // How long from `now` until the next attempt may start (zero when it may start now).
  Clock::duration wait(Clock::time_point now) const;

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds max_;
  int failures_ = 0;
  Clock::time_point last_failure_{};
};

}  // namespace binpick::acquisition
