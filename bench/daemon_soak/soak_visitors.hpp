#pragma once
// The other robots of the soak (a monitoring PC, a second controller): each connects, asks STATUS
// and PING, now and then reports a FAILED pick, and leaves, again and again, on its own thread,
// while the main robot runs its cycles.
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "reply_tally.hpp"

namespace binpick::bench::soak {

class Visitors {
 public:
  Visitors(int port, ReplyTally& tally, int count, std::chrono::milliseconds reply_timeout);
  ~Visitors() { stop(); }
  Visitors(const Visitors&) = delete;
  Visitors& operator=(const Visitors&) = delete;
  void stop();
  long visits() const { return visits_; }

 private:
  void visitAgainAndAgain(int index);
  void pause(std::chrono::milliseconds duration) const;

  int port_;
  ReplyTally& tally_;
  std::chrono::milliseconds reply_timeout_;
  std::atomic<bool> stopping_{false};
  std::atomic<long> visits_{0};
  std::vector<std::thread> threads_;
};

}  // namespace binpick::bench::soak
