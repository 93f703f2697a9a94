#pragma once
// Test support: a CellService driven directly (no TCP), its replies collected per client.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "binpick/cell/cell_service.hpp"

namespace binpick::cell::testing {

class ReplyCollector {
 public:
  ReplySink sink() {
    return [this](robot::ClientId client, const robot::Reply& reply) {
      std::lock_guard lock(mutex_);
      replies_.push_back({client, reply});
      arrived_.notify_all();
    };
  }
  // The next reply to `client`; nullopt after `timeout`.
  std::optional<robot::Reply> next(robot::ClientId client,
                                   std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
    std::unique_lock lock(mutex_);
    std::optional<robot::Reply> found;
    arrived_.wait_for(lock, timeout, [&] {
      for (auto it = replies_.begin(); it != replies_.end(); ++it) {
        if (it->first != client) continue;
        found = it->second;
        replies_.erase(it);
        return true;
      }
      return false;
    });
    return found;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<std::pair<robot::ClientId, robot::Reply>> replies_;
};

inline robot::Request request(robot::Command command, std::optional<std::string> argument = std::nullopt) {
  return robot::Request{command, std::move(argument)};
}

}  // namespace binpick::cell::testing
