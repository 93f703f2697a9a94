#pragma once
// Where a guided hand-eye session's images come from: the cell's camera, one software-triggered
// frame per view, or the images of a views directory served one per view (the virtual cell's
// camera, for demos and tests without hardware).
//
// Thread-safety: a ViewCamera is used from one thread.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "binpick/acquisition/camera.hpp"

namespace binpick::cli {

class ViewCamera {
 public:
  virtual ~ViewCamera() = default;
  // The next image, 8- or 16-bit grey. Throws core::Error saying what failed; the camera stays
  // usable, and the next call tries again.
  virtual cv::Mat grab() = 0;
  virtual std::string description() const = 0;
};

// DIR/*.png (not its subdirectories) in name order, one per grab; once all were served, grab()
// throws. Throws core::Error when DIR holds no PNG image.
std::unique_ptr<ViewCamera> makeReplayViewCamera(const std::string& directory);

// One frame per grab: trigger, then wait up to timeout_ms. The camera is opened on the first grab.
// After any failed frame it is closed and opened afresh on the next grab, so that a frame that
// arrives late is never taken for the next view's.
std::unique_ptr<ViewCamera> makeLiveViewCamera(std::unique_ptr<acquisition::Camera> camera, int timeout_ms);

}  // namespace binpick::cli
