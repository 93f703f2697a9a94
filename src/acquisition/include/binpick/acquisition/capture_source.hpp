#pragma once
// Where the cell's captures come from: the live camera + projector, or recorded capture
// directories (replay). Everything after the capture is the same code either way.
//
// Thread-safety: a source is used from one thread.
#include <memory>
#include <string>
#include <vector>

#include "binpick/acquisition/camera.hpp"
#include "binpick/acquisition/projector.hpp"
#include "binpick/acquisition/sequencer.hpp"
#include "binpick/core/cancellation.hpp"
#include "binpick/io/capture.hpp"

namespace binpick::acquisition {

class CaptureSource {
 public:
  virtual ~CaptureSource() = default;
  // The next capture. Throws core::Error (CaptureError for camera faults) naming the reason, or
  // core::Cancelled once `cancel` is set (a live capture stops before its next pattern); the
  // source stays usable for the next call.
  io::Capture next(const core::CancelFlag* cancel = nullptr) { return nextCapture(cancel); }
  virtual std::string description() const = 0;

 private:
  virtual io::Capture nextCapture(const core::CancelFlag* cancel) = 0;
};

struct ReplayParams {
  std::string path;   // a capture directory, or a directory of capture directories
  bool loop = false;  // start again after the last one (else next() throws at the end)
  int threads = 0;    // image decoding threads (0: all cores)
};

// Replays capture directories in name order, bit-identical to what was recorded. A path that holds
// no capture yet (missing or empty) makes every next() throw core::Error saying so, until one is
// there; a subdirectory without capture.json (a recording that did not finish) throws here.
std::unique_ptr<CaptureSource> makeReplaySource(const ReplayParams& params);

struct LiveParams {
  io::PatternSetSpec patterns;
  SequencerParams sequencer;
  // After a lost connection, reopening is tried at most every reopen_backoff_ms, doubling up to
  // max_reopen_backoff_ms while it keeps failing.
  int reopen_backoff_ms = 500;
  int max_reopen_backoff_ms = 8000;
};

// The live path: opens the camera on the first next(); after a fault it reopens the camera (with
// backoff) before the following capture.
std::unique_ptr<CaptureSource> makeLiveSource(std::unique_ptr<Camera> camera,
                                              std::unique_ptr<ProjectorTrigger> projector, const LiveParams& params);

}  // namespace binpick::acquisition
