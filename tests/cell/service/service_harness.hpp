#pragma once
// Test support: a CellService driven directly (no TCP) on the virtual cell's bin, its replies
// collected per client.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "binpick/cell/cell_service.hpp"
#include "binpick/io/capture.hpp"
#include "cell_scene.hpp"

namespace binpick::cell::testing {

class ReplyCollector {
 public:
  ReplySink sink() {
    return [this](robot::ClientId client, const robot::Reply& reply) {
      std::unique_lock lock(mutex_);
      replies_.push_back({client, reply});
      arrived_.notify_all();
      if (hold_at_ && reply.command == *hold_at_) {
        hold_at_.reset();
        held_ = true;
        arrived_.notify_all();
        arrived_.wait(lock, [&] { return !held_; });
      }
    };
  }
  // The next `command` reply, once collected, holds the thread that sends it until release():
  // the cell's cycle thread sends the replies to the robots waiting on its cycle, so a test can
  // act in the moment right after a cycle answered, as deterministically as a race allows.
  void holdAt(robot::Command command) {
    std::lock_guard lock(mutex_);
    hold_at_ = command;
  }
  void waitUntilHeld() {
    std::unique_lock lock(mutex_);
    arrived_.wait(lock, [&] { return held_; });
  }
  void release() {
    std::lock_guard lock(mutex_);
    held_ = false;
    arrived_.notify_all();
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
  std::optional<robot::Command> hold_at_;
  bool held_ = false;
};

inline robot::Request request(robot::Command command, std::optional<std::string> argument = std::nullopt) {
  return robot::Request{command, std::move(argument)};
}

constexpr robot::ClientId kRobot = 1;

inline std::shared_ptr<const CellSetup> setupFor(const std::string& yaml) {
  return prepareCell(parseCellConfig(yaml, "cell.yaml", cellScene().directory));
}

// Settings text whose rig calibration file does not exist.
inline std::string withoutRigCalibration(std::string yaml) {
  return yaml.replace(yaml.find("calibration: "), 13, "calibration: /nonexistent/");
}

// A service on the scene's bin with its replies collected.
struct Cell {
  explicit Cell(const std::string& yaml) : Cell(setupFor(yaml)) {}
  explicit Cell(std::shared_ptr<const CellSetup> prepared)
      : setup(std::move(prepared)), service(setup, makeCaptureSource(setup->config.source), collector.sink()) {}
  Cell(const std::string& yaml, std::unique_ptr<acquisition::CaptureSource> source)
      : setup(setupFor(yaml)), service(setup, std::move(source), collector.sink()) {}

  robot::Reply ask(const robot::Request& r, robot::ClientId client = kRobot) {
    service.handle(client, r);
    const auto reply = collector.next(client);
    if (!reply) throw std::runtime_error("no reply");
    return *reply;
  }
  std::vector<robot::Reply> allPicks(robot::ClientId client = kRobot) {
    std::vector<robot::Reply> picks;
    for (robot::Reply r = ask(request(robot::Command::NextPick), client); r.status == robot::Status::Ok;
         r = ask(request(robot::Command::NextPick), client)) {
      picks.push_back(r);
    }
    return picks;
  }

  ReplyCollector collector;
  std::shared_ptr<const CellSetup> setup;
  CellService service;
};

// A camera that takes its time.
class SlowSource : public acquisition::CaptureSource {
 public:
  explicit SlowSource(std::chrono::milliseconds delay) : delay_(delay) {}
  std::string description() const override { return "slow"; }

 private:
  io::Capture nextCapture(const core::CancelFlag* /*cancel*/) override {
    std::this_thread::sleep_for(delay_);
    return io::readCapture(cellScene().capture);
  }
  std::chrono::milliseconds delay_;
};

}  // namespace binpick::cell::testing
