#include "notify_listener.hpp"

#include <algorithm>
#include <string>

namespace binpick::bench::soak {

using namespace std::chrono_literals;

NotifyListener::NotifyListener(cell::testing::NotifySocket& socket) : socket_(socket) {
  thread_ = std::thread([this] { listen(); });
}

NotifyListener::~NotifyListener() {
  stopping_ = true;
  thread_.join();
}

void NotifyListener::listen() {
  while (!stopping_) {
    const std::optional<std::string> message = socket_.receive(100ms);
    if (!message || message->find("READY=1") == std::string::npos) continue;
    std::lock_guard lock(mutex_);
    ready_times_.push_back(Clock::now());
    ready_.notify_all();
  }
}

std::optional<NotifyListener::Clock::time_point> NotifyListener::readyAfter(Clock::time_point since,
                                                                             std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  std::optional<Clock::time_point> found;
  ready_.wait_for(lock, timeout, [&] {
    const auto after = std::find_if(ready_times_.begin(), ready_times_.end(), [&](auto t) { return t > since; });
    if (after != ready_times_.end()) found = *after;
    return found.has_value();
  });
  return found;
}

}  // namespace binpick::bench::soak
