#pragma once
// Wall-clock time of a stage in milliseconds, on the monotonic clock (never jumps with NTP).
// Timings are reported, never used for decisions (deadlines use the clock directly).
#include <chrono>

namespace binpick::core {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : start_(Clock::now()) {}

  // Milliseconds since construction or the last lap.
  double elapsedMs() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }

  // elapsedMs(), then starts again: consecutive stages timed with one stopwatch.
  double lapMs() {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  Clock::time_point start_;
};

}  // namespace binpick::core
