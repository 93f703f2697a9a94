#pragma once
// A GigE Vision camera without hardware: Aravis's fake camera, run in this process on a loopback
// address, serving images we hand it. The whole live path (GigE Vision control and streaming,
// buffers, the sequencer, recording) runs against it in tests and demos. Quirks of the fake
// (Aravis 0.8): software trigger only; one fake per address (it binds UDP port 3956), so tests
// that use one must not run at the same time (ctest RESOURCE_LOCK).
//
// Thread-safety: serve() and the fault switches may be called from any thread; the camera serves
// frames from Aravis's own threads.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "binpick/acquisition/projector.hpp"

namespace binpick::acquisition {

struct FakeCameraParams {
  std::string address = "127.0.0.1";  // interface address the fake listens on
  std::string serial = "BINPICK-FAKE-0";
  int width = 1280;
  int height = 1024;
  bool sixteen_bit = false;  // Mono16 instead of Mono8
};

class FakeGigECamera {
 public:
  // Starts serving. Throws core::Error when the address cannot be bound (another fake camera
  // or GigE Vision tool on it), or naming the Aravis plugin when it cannot be loaded.
  explicit FakeGigECamera(const FakeCameraParams& params);
  ~FakeGigECamera();
  FakeGigECamera(const FakeGigECamera&) = delete;
  FakeGigECamera& operator=(const FakeGigECamera&) = delete;

  // The image every following frame shows (CV_8UC1 or CV_16UC1 of the camera's size; copied).
  void serve(const cv::Mat& image);
  // What CameraParams::id needs to find this camera.
  std::string id() const;

  // Faults, for tests. Share of stream packets the fake drops, drawn from GLib's global random
  // generator, which `seed` reseeds. Aravis 0.8's fake ignores resend requests: a frame that lost
  // a packet arrives Incomplete.
  void setPacketLoss(double ratio, unsigned seed = 1);
  // Stops answering control requests (as if unplugged) until resumed: revokes the client's
  // control (its heartbeat emits control-lost within about a second), then shuts the fake's
  // server down. Blocks for about 1.3 s. resume() starts a fresh server with the same settings
  // and image; clients must open() again.
  void suspend();
  void resume();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A projector that makes the fake camera serve image k when asked to show pattern k: the
// "virtual projector" in front of the fake camera.
std::unique_ptr<ProjectorTrigger> makeVirtualProjector(FakeGigECamera& camera, std::vector<cv::Mat> pattern_images);

}  // namespace binpick::acquisition
