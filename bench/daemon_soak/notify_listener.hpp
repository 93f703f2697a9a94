#pragma once
// binpickd's messages to its service manager, read all the time as systemd reads them: a socket
// nobody reads fills up (binpickd then logs that it cannot notify, and a READY=1 is lost), and a
// READY=1 is timed when it comes, not when the soak gets round to looking.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "daemon_process.hpp"

namespace binpick::bench::soak {

class NotifyListener {
 public:
  using Clock = std::chrono::steady_clock;
  explicit NotifyListener(cell::testing::NotifySocket& socket);
  ~NotifyListener();
  NotifyListener(const NotifyListener&) = delete;
  NotifyListener& operator=(const NotifyListener&) = delete;
  // When the first READY=1 after `since` came; nullopt when none has come within `timeout`.
  std::optional<Clock::time_point> readyAfter(Clock::time_point since, std::chrono::milliseconds timeout);

 private:
  void listen();

  cell::testing::NotifySocket& socket_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<Clock::time_point> ready_times_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace binpick::bench::soak
