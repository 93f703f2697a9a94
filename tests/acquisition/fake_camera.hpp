#pragma once
// In-memory test doubles of the camera and the projector: the camera serves the image of the
// pattern the projector last showed, and fails on cue (a dropped or incomplete frame, a pattern
// that always times out, a lost connection, opens that fail). Both share one FakeRigState, which
// the test keeps to script faults and read counters after the source took ownership of the
// doubles. Single-threaded, like the interfaces they implement.
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "binpick/acquisition/camera.hpp"
#include "binpick/acquisition/projector.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition::testing {

struct FakeRigState {
  std::vector<cv::Mat> images;  // served for pattern k: images[k]
  // The camera takes its trigger from the projector's pulse (TriggerOrder::CameraOnly); its
  // trigger() is then a no-op, as the Camera interface says of hardware triggers.
  bool hardware_trigger = false;

  // Faults. Frames are numbered by grab() calls since construction, from 0.
  std::map<uint64_t, FrameStatus> frame_faults;  // frame number -> the status it gets instead of Ok
  int failing_pattern = -1;                      // every frame of this pattern times out
  uint64_t lose_connection_at = std::numeric_limits<uint64_t>::max();  // this frame and on, until open()
  int failing_opens = 0;                                               // the next open() calls that throw

  // What happened.
  int shown = -1;              // pattern on show
  std::vector<int> shown_log;  // every showPattern() index
  uint64_t grabs = 0;
  int triggers = 0;          // trigger() calls that armed the camera
  int pending_triggers = 0;  // armed and not yet grabbed
  int open_attempts = 0;
  int opens = 0;  // successful
  int closes = 0;
  bool open = false;
  bool started = false;
  bool connection_lost = false;
};

class FakeCamera : public Camera {
 public:
  explicit FakeCamera(std::shared_ptr<FakeRigState> state) : state_(std::move(state)) {}

  void open() override {
    ++state_->open_attempts;
    if (state_->failing_opens > 0) {
      --state_->failing_opens;
      throw core::Error("fake camera 'FAKE-0001': not found on any interface");
    }
    ++state_->opens;
    state_->open = true;
    state_->connection_lost = false;
    state_->pending_triggers = 0;  // a reopened camera forgets triggers it never answered
  }
  void close() override {
    if (state_->open) ++state_->closes;
    state_->open = false;
    state_->started = false;
  }
  bool isOpen() const override { return state_->open; }
  void start() override {
    if (!state_->open) throw core::Error("fake camera 'FAKE-0001': start() before open()");
    state_->started = true;
  }
  void stop() override { state_->started = false; }

  void trigger() override {
    if (state_->hardware_trigger) return;
    if (state_->connection_lost) throw core::Error("fake camera 'FAKE-0001': not connected");
    ++state_->triggers;
    ++state_->pending_triggers;
  }

  Frame grab(int /*timeout_ms*/) override {
    FakeRigState& s = *state_;
    Frame frame;
    frame.frame_id = s.grabs++;
    if (!s.started) return failure(frame, FrameStatus::Failed, "not streaming");
    if (frame.frame_id == s.lose_connection_at) s.connection_lost = true;
    if (s.connection_lost) return failure(frame, FrameStatus::ConnectionLost, "heartbeat timeout");
    if (s.pending_triggers == 0) return failure(frame, FrameStatus::Timeout, "no trigger");
    --s.pending_triggers;  // the exposure happened; what follows only decides how the frame arrives
    const auto fault = s.frame_faults.find(frame.frame_id);
    if (fault != s.frame_faults.end()) return failure(frame, fault->second, "scripted");
    if (s.shown == s.failing_pattern) return failure(frame, FrameStatus::Timeout, "scripted");
    if (s.shown < 0 || s.shown >= static_cast<int>(s.images.size())) {
      return failure(frame, FrameStatus::Failed, "no image for pattern " + std::to_string(s.shown));
    }
    frame.status = FrameStatus::Ok;
    frame.image = s.images[static_cast<std::size_t>(s.shown)].clone();
    return frame;
  }

  bool connectionLost() const override { return state_->connection_lost; }
  StreamStatistics statistics() const override { return {}; }
  std::string description() const override { return "Fake Vision FV-1 FAKE-0001"; }

 private:
  static Frame failure(Frame frame, FrameStatus status, std::string detail) {
    frame.status = status;
    frame.detail = std::move(detail);
    return frame;
  }

  std::shared_ptr<FakeRigState> state_;
};

class FakeProjector : public ProjectorTrigger {
 public:
  explicit FakeProjector(std::shared_ptr<FakeRigState> state) : state_(std::move(state)) {}
  void showPattern(int index) override {
    state_->shown = index;
    state_->shown_log.push_back(index);
    if (state_->hardware_trigger) ++state_->pending_triggers;  // its sync output fires the camera
  }
  std::string description() const override { return "fake projector"; }

 private:
  std::shared_ptr<FakeRigState> state_;
};

}  // namespace binpick::acquisition::testing
