#pragma once
// The capture sequencer: for each pattern of a set, show it, let the light settle, trigger the
// camera and take exactly one whole frame, re-triggering a bounded number of times when a frame
// is lost or incomplete. The result is a Capture (binpick/io/capture.hpp) ready for the decoder
// or for writeCapture (record mode).
//
// Thread-safety: a sequencer drives one camera and one projector from the calling thread.
#include <string>
#include <vector>

#include "binpick/acquisition/camera.hpp"
#include "binpick/acquisition/projector.hpp"
#include "binpick/core/cancellation.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"

namespace binpick::acquisition {

enum class TriggerOrder {
  ProjectorThenCamera,  // pulse the projector, wait settle_us, trigger the camera
  CameraOnly,           // the projector triggers the camera (hardware line): only pulse it
};

struct SequencerParams {
  int settle_us = 2000;         // after a new pattern, before the camera exposes
  int frame_timeout_ms = 1000;  // per frame
  int max_retries = 2;          // extra triggers for one pattern's lost frame
  TriggerOrder order = TriggerOrder::ProjectorThenCamera;
  void validate() const;  // throws core::Error naming the field
};

struct SequencerReport {
  int retries = 0;                         // extra triggers over the whole capture
  std::vector<std::string> retry_reasons;  // "pattern 12 (gray_col_05): timeout", ...
  double milliseconds = 0.0;               // whole capture
};

// Thrown when a capture cannot be completed: names the pattern and what the camera said.
class CaptureError : public core::Error {
 public:
  CaptureError(const std::string& message, bool connection_lost)
      : core::Error(message), connection_lost_(connection_lost) {}
  bool connectionLost() const { return connection_lost_; }

 private:
  bool connection_lost_;
};

class CaptureSequencer {
 public:
  // Throws core::Error on invalid params.
  CaptureSequencer(Camera& camera, ProjectorTrigger& projector, const SequencerParams& params);
  // Captures every pattern of `patterns` (the camera must be open and started). Throws
  // CaptureError naming the pattern when a frame stays lost after the retries, or the camera is
  // gone; the images have the camera's size and depth, the metadata says what was projected.
  // When the previous capture stopped after k of its n patterns, the projector is first pulsed
  // n - k times so that it wraps back to its first pattern (frames these pulses trigger are
  // dropped); a warning says so. Once `cancel` is set (the cycle's deadline passed, the service
  // stops) the capture ends before its next pattern, or its next retry, with core::Cancelled: at
  // most one frame_timeout_ms later. The next capture then resynchronises the projector as after
  // any capture that stopped part-way.
  io::Capture capture(const io::PatternSetSpec& patterns, SequencerReport* report = nullptr,
                      const core::CancelFlag* cancel = nullptr);

 private:
  void resynchroniseProjector();

  Camera& camera_;
  ProjectorTrigger& projector_;
  SequencerParams params_;
  // Where the projector stands in its sequence of sequence_length_ patterns: patterns pulsed
  // since it last showed its first one. 0 after every complete capture.
  std::size_t projector_position_ = 0;
  std::size_t sequence_length_ = 0;
};

}  // namespace binpick::acquisition
