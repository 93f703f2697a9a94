#pragma once
// Cooperative cancellation of a long computation (a pick cycle past its deadline, a service that
// is stopping). Whoever owns the work calls cancel(); the work polls the flag between its stages
// and, at a coarse grain, inside its loops, and gives up by throwing Cancelled. Inside a parallel
// loop the remaining iterations are skipped and the throw comes after the loop: an exception must
// not leave an OpenMP region. A null flag is never cancelled.
// Thread-safety: cancel() and cancelled() may be called from any thread.
#include <atomic>
#include <stdexcept>
#include <string>

namespace binpick::core {

// Not a core::Error: nothing was wrong with the input, the result was no longer wanted.
class Cancelled : public std::runtime_error {
 public:
  explicit Cancelled(const std::string& where) : std::runtime_error("cancelled " + where) {}
};

class CancelFlag {
 public:
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

inline bool isCancelled(const CancelFlag* flag) { return flag != nullptr && flag->cancelled(); }

// Throws Cancelled("WHERE") when `flag` is set; `where` says at which point ("before detection").
inline void throwIfCancelled(const CancelFlag* flag, const char* where) {
  if (isCancelled(flag)) throw Cancelled(where);
}

}  // namespace binpick::core
