#pragma once
// Internal to the Aravis plugin: Aravis's fake GigE Vision camera serving our images, behind the
// public FakeGigECamera (fake_gige_camera.hpp says what each call does).
#include <memory>
#include <opencv2/core.hpp>

#include "binpick/acquisition/fake_gige_camera.hpp"

namespace binpick::acquisition::detail {

class FakeGigEServer {
 public:
  explicit FakeGigEServer(const FakeCameraParams& params);
  ~FakeGigEServer();
  FakeGigEServer(const FakeGigEServer&) = delete;
  FakeGigEServer& operator=(const FakeGigEServer&) = delete;

  void serve(const cv::Mat& image);
  void setPacketLoss(double ratio, unsigned seed);
  void suspend();
  void resume();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace binpick::acquisition::detail
