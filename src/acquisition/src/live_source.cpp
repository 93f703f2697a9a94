// The live source: the sequencer on a camera that is opened lazily and reopened after it was lost.
#include <chrono>
#include <memory>
#include <string>
#include <utility>

#include "backoff.hpp"
#include "binpick/acquisition/capture_source.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition {
namespace {

using Clock = Backoff::Clock;

void validateLive(const LiveParams& params) {
  const std::string owner = "live params";
  core::requireField(params.reopen_backoff_ms >= 1, owner, "reopen_backoff_ms", ">= 1", params.reopen_backoff_ms);
  core::requireField(params.max_reopen_backoff_ms >= params.reopen_backoff_ms, owner, "max_reopen_backoff_ms",
                     ">= reopen_backoff_ms", params.max_reopen_backoff_ms);
  params.patterns.validate();
  params.sequencer.validate();
}

long long toMilliseconds(Clock::duration duration) {
  return std::chrono::ceil<std::chrono::milliseconds>(duration).count();
}

class LiveSource : public CaptureSource {
 public:
  LiveSource(std::unique_ptr<Camera> camera, std::unique_ptr<ProjectorTrigger> projector, const LiveParams& params)
      : camera_(std::move(camera)),
        projector_(std::move(projector)),
        params_(params),
        sequencer_(*camera_, *projector_, params.sequencer),
        backoff_(std::chrono::milliseconds(params.reopen_backoff_ms),
                 std::chrono::milliseconds(params.max_reopen_backoff_ms)) {}

  ~LiveSource() override { shutDown(); }

  std::string description() const override { return "live: " + cameraName() + ", " + projector_->description(); }

 private:
  io::Capture nextCapture(const core::CancelFlag* cancel) override {
    ensureStreaming();
    try {
      return sequencer_.capture(params_.patterns, nullptr, cancel);
    } catch (const CaptureError& e) {
      // A lost camera is closed now and reopened by the next call; any other fault (a frame that
      // stayed lost) leaves it streaming.
      if (e.connectionLost() || camera_->connectionLost()) {
        core::componentLogger("live source")
            ->warn("{}: connection lost, reopening before the next capture: {}", cameraName(), e.what());
        shutDown();
        backoff_.failed(Clock::now());
      }
      throw;
    }
  }

  std::string cameraName() const {
    try {
      const std::string name = camera_->description();
      if (!name.empty()) return "camera '" + name + "'";
    } catch (const std::exception&) {
      // A camera that cannot even describe itself is still "the camera" in a message.
    }
    return "camera";
  }

  // Opens and starts the camera unless it streams already. Within the backoff of earlier failures
  // it does not try and does not wait either: it fails at once, so that a robot's TRIGGER hears
  // no_image now rather than after a sleep of up to max_reopen_backoff_ms that nothing could
  // interrupt. A failure is thrown; a call after the backoff tries again.
  void ensureStreaming() {
    if (streaming_) return;
    const Clock::duration wait = backoff_.wait(Clock::now());
    if (wait > Clock::duration::zero()) {
      throw CaptureError("live source: " + cameraName() + " is away; the next attempt to reopen it is in " +
                             std::to_string(toMilliseconds(wait)) + " ms",
                         true);
    }
    try {
      camera_->open();
      camera_->start();
    } catch (const std::exception& e) {
      shutDown();
      backoff_.failed(Clock::now());
      ++failed_opens_;
      const std::string message = "live source: " + cameraName() + " did not open (attempt " +
                                  std::to_string(failed_opens_) + ", next in " +
                                  std::to_string(backoff_.delay().count()) + " ms): " + e.what();
      core::componentLogger("live source")->warn("{}", message);
      throw CaptureError(message, true);
    }
    if (backoff_.failures() > 0)
      core::componentLogger("live source")->info("{}: streaming again", cameraName());  // after a fault
    backoff_.succeeded();
    failed_opens_ = 0;
    streaming_ = true;
  }

  // Stops and closes whatever is open; a lost camera may refuse either, which changes nothing.
  void shutDown() noexcept {
    streaming_ = false;
    try {
      if (!camera_->isOpen()) return;
    } catch (const std::exception&) {
      return;
    }
    try {
      camera_->stop();
    } catch (const std::exception& e) {
      core::componentLogger("live source")->debug("{}: stop: {}", cameraName(), e.what());
    }
    try {
      camera_->close();
    } catch (const std::exception& e) {
      core::componentLogger("live source")->debug("{}: close: {}", cameraName(), e.what());
    }
  }

  std::unique_ptr<Camera> camera_;
  std::unique_ptr<ProjectorTrigger> projector_;
  LiveParams params_;
  CaptureSequencer sequencer_;
  Backoff backoff_;
  bool streaming_ = false;
  int failed_opens_ = 0;  // in a row, for messages (the backoff also counts the loss itself)
};

}  // namespace

std::unique_ptr<CaptureSource> makeLiveSource(std::unique_ptr<Camera> camera,
                                              std::unique_ptr<ProjectorTrigger> projector, const LiveParams& params) {
  if (!camera) throw core::Error("live source: no camera");
  if (!projector) throw core::Error("live source: no projector trigger");
  validateLive(params);
  return std::make_unique<LiveSource>(std::move(camera), std::move(projector), params);
}

}  // namespace binpick::acquisition
