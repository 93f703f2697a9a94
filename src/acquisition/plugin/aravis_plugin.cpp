// The Aravis plugin's table (src/aravis_plugin_abi.hpp): the camera and the fake camera.
#include "aravis_camera.hpp"
#include "aravis_plugin_abi.hpp"
#include "fake_gige_server.hpp"

namespace binpick::acquisition::detail {
namespace {

FakeGigEServer* startFake(const FakeCameraParams& params) { return new FakeGigEServer(params); }
void stopFake(FakeGigEServer* fake) { delete fake; }
void serve(FakeGigEServer& fake, const cv::Mat& image) { fake.serve(image); }
void setPacketLoss(FakeGigEServer& fake, double ratio, unsigned seed) { fake.setPacketLoss(ratio, seed); }
void suspend(FakeGigEServer& fake) { fake.suspend(); }
void resume(FakeGigEServer& fake) { fake.resume(); }

const AravisPlugin kPlugin{kAravisPluginVersion, newAravisCamera, startFake, stopFake, serve,
                           setPacketLoss,        suspend,         resume};

}  // namespace
}  // namespace binpick::acquisition::detail

extern "C" const binpick::acquisition::detail::AravisPlugin* binpick_aravis() {
  return &binpick::acquisition::detail::kPlugin;
}
