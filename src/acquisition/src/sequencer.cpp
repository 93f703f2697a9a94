// CaptureSequencer::capture: one whole camera frame per projected pattern, with bounded retries.
#include <chrono>
#include <string>
#include <thread>
#include <utility>

#include "binpick/acquisition/sequencer.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::acquisition {
namespace {

std::string patternLabel(std::size_t index, const std::string& name) {
  return "pattern " + std::to_string(index) + " (" + name + ")";
}

std::string statusText(const Frame& frame) {
  std::string text = frameStatusName(frame.status);
  if (!frame.detail.empty()) text += " (" + frame.detail + ")";
  return text;
}

int bitDepth(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return 8;
  if (image.type() == CV_16UC1) return 16;
  return 0;
}

std::string formatText(const cv::Mat& image) {
  const int depth = bitDepth(image);
  const std::string kind =
      depth == 0 ? "OpenCV type " + std::to_string(image.type()) : std::to_string(depth) + "-bit grey";
  return std::to_string(image.cols) + "x" + std::to_string(image.rows) + " " + kind;
}

// The projector holds a pattern until the next pulse, so a failed pulse means the images would no
// longer match their pattern names: the capture cannot go on.
void showPattern(ProjectorTrigger& projector, int index, const std::string& label) {
  try {
    projector.showPattern(index);
  } catch (const std::exception& e) {
    throw CaptureError(label + ": projector '" + projector.description() + "' failed: " + e.what(), false);
  }
}

// With CameraOnly the projector's pulse triggers the camera; a retry still calls trigger(), which
// a hardware- or free-running camera ignores while it waits for its next frame.
void triggerCamera(Camera& camera, const SequencerParams& params, int attempt, const std::string& label) {
  if (params.order == TriggerOrder::CameraOnly && attempt == 0) return;
  try {
    camera.trigger();
  } catch (const std::exception& e) {
    throw CaptureError(label + ": camera trigger failed: " + e.what(), camera.connectionLost());
  }
}

// A frame that timed out may still arrive later, and would then be taken for the answer to the
// next trigger (or the next pattern): before re-triggering, drop whatever is already waiting.
void dropLateFrames(Camera& camera) {
  constexpr int kMostFramesWaiting = 256;  // CameraParams::buffers is at most that
  for (int i = 0; i < kMostFramesWaiting; ++i) {
    if (camera.grab(0).status == FrameStatus::Timeout) return;
  }
}

// One whole frame of the pattern on show, re-triggering up to max_retries times. A lost
// connection ends the capture at once: retrying cannot help until the camera is reopened.
cv::Mat takeFrame(Camera& camera, const SequencerParams& params, const std::string& label, SequencerReport& report,
                  const core::CancelFlag* cancel) {
  Frame frame;
  for (int attempt = 0; attempt <= params.max_retries; ++attempt) {
    if (attempt > 0) {
      core::throwIfCancelled(cancel, "during the capture, before a retry");
      std::string reason = label + ": " + statusText(frame);
      core::componentLogger("sequencer")->warn("retry {} of {}: {}", attempt, params.max_retries, reason);
      ++report.retries;
      report.retry_reasons.push_back(std::move(reason));
      if (frame.status == FrameStatus::Timeout) dropLateFrames(camera);
    }
    triggerCamera(camera, params, attempt, label);
    frame = camera.grab(params.frame_timeout_ms);
    if (frame.status == FrameStatus::Ok && frame.image.empty()) {
      frame.status = FrameStatus::Failed;  // a camera bug, but the next frame may be fine
      frame.detail = "an ok frame without pixels";
    }
    if (frame.status == FrameStatus::Ok) return std::move(frame.image);
    if (frame.status == FrameStatus::ConnectionLost || camera.connectionLost()) {
      const bool said_so = frame.status == FrameStatus::ConnectionLost;
      const std::string why = said_so ? frame.detail : "last frame: " + statusText(frame);
      throw CaptureError(label + ": camera connection lost" + (why.empty() ? "" : " (" + why + ")"), true);
    }
  }
  throw CaptureError(label + ": no whole frame after " + std::to_string(params.max_retries + 1) +
                         " triggers; last: " + statusText(frame),
                     false);
}

// Every image of a capture must share the first one's size and depth: the decoder compares them
// pixel by pixel.
void checkFormat(const cv::Mat& image, const cv::Mat& first, const std::string& label) {
  if (bitDepth(image) == 0) {
    throw CaptureError(
        label + ": the camera delivered a " + formatText(image) + " image; captures take 8- or 16-bit grey", false);
  }
  if (image.size() != first.size() || image.type() != first.type()) {
    throw CaptureError(
        label + ": the camera delivered a " + formatText(image) + " image after a " + formatText(first) + " one",
        false);
  }
}

}  // namespace

CaptureSequencer::CaptureSequencer(Camera& camera, ProjectorTrigger& projector, const SequencerParams& params)
    : camera_(camera), projector_(projector), params_(params) {
  params_.validate();
}

void CaptureSequencer::resynchroniseProjector() {
  if (projector_position_ == 0 || !projector_.advancesOnPulse()) return;
  core::componentLogger("sequencer")
      ->warn("the last capture stopped after {} of {} patterns: pulsing the projector {} times to its first pattern",
             projector_position_, sequence_length_, sequence_length_ - projector_position_);
  for (std::size_t k = projector_position_; k < sequence_length_; ++k) {
    showPattern(projector_, static_cast<int>(k), "resynchronising the projector");
    projector_position_ = k + 1;
    if (params_.settle_us > 0) std::this_thread::sleep_for(std::chrono::microseconds(params_.settle_us));
  }
  projector_position_ = 0;
  dropLateFrames(camera_);  // a projector that triggers the camera made frames of them
}

io::Capture CaptureSequencer::capture(const io::PatternSetSpec& patterns, SequencerReport* report,
                                      const core::CancelFlag* cancel) {
  patterns.validate();
  resynchroniseProjector();
  const core::Stopwatch stopwatch;
  SequencerReport local;
  SequencerReport& out = report != nullptr ? *report : local;
  out = SequencerReport{};

  io::Capture capture;
  capture.metadata.timestamp = io::utcTimestamp();  // when the first pattern was shown
  capture.metadata.patterns = reconstruction::patternNames(patterns);
  const std::vector<std::string>& names = capture.metadata.patterns;
  sequence_length_ = names.size();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string label = patternLabel(k, names[k]);
    core::throwIfCancelled(cancel, "during the capture");  // the projector resynchronises next time
    showPattern(projector_, static_cast<int>(k), label);
    projector_position_ = k + 1;
    if (params_.order == TriggerOrder::ProjectorThenCamera && params_.settle_us > 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(params_.settle_us));
    }
    cv::Mat image = takeFrame(camera_, params_, label, out, cancel);
    checkFormat(image, capture.images.empty() ? image : capture.images.front(), label);
    capture.images.push_back(std::move(image));
    capture.metadata.frame_times_ms.push_back(stopwatch.elapsedMs());  // since the capture began, not per frame
  }
  projector_position_ = 0;  // the sequence is complete: the next pulse shows its first pattern

  io::CaptureMetadata& m = capture.metadata;
  m.source = camera_.description();
  m.image_width = capture.images.front().cols;
  m.image_height = capture.images.front().rows;
  m.bit_depth = bitDepth(capture.images.front());
  m.pattern_set = patterns;
  out.milliseconds = stopwatch.elapsedMs();
  core::componentLogger("sequencer")
      ->info("captured {} images ({}x{}, {}-bit) from {} in {:.0f} ms, {} retries", capture.images.size(),
             m.image_width, m.image_height, m.bit_depth, m.source, out.milliseconds, out.retries);
  return capture;
}

}  // namespace binpick::acquisition

// SequencerParams::validate.
namespace binpick::acquisition {

void SequencerParams::validate() const {
  const std::string owner = "sequencer params";
  // Bounds catch unit mistakes (seconds for microseconds) rather than limit real rigs.
  core::requireField(settle_us >= 0 && settle_us <= 10000000, owner, "settle_us", "in [0, 10000000]", settle_us);
  core::requireField(frame_timeout_ms >= 1 && frame_timeout_ms <= 600000, owner, "frame_timeout_ms", "in [1, 600000]",
                     frame_timeout_ms);
  core::requireField(max_retries >= 0 && max_retries <= 100, owner, "max_retries", "in [0, 100]", max_retries);
  core::requireField(order == TriggerOrder::ProjectorThenCamera || order == TriggerOrder::CameraOnly, owner, "order",
                     "ProjectorThenCamera or CameraOnly", static_cast<int>(order));
}

}  // namespace binpick::acquisition
