// makeAravisCamera and FakeGigECamera through the Aravis plugin (aravis_plugin_abi.hpp says why a
// plugin).
#include "aravis_plugin_abi.hpp"
#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/plugin.hpp"

namespace binpick::acquisition {
namespace {

// Loaded by the first camera of the process, never unloaded.
const detail::AravisPlugin& aravis() {
  // The plugin has its own copy of the component-logger registry: loggers it finds already
  // registered (with spdlog, shared) carry the sinks the program added (binpickd's web view).
  core::componentLogger("camera");
  core::componentLogger("fake camera");
  return core::loadPlugin<detail::AravisPlugin>(BINPICK_ARAVIS_BESIDE_PROGRAM, BINPICK_ARAVIS_IN_BUILD,
                                                detail::kAravisPluginEntry, detail::kAravisPluginVersion,
                                                "camera: binpick's Aravis plugin");
}

}  // namespace

std::unique_ptr<Camera> makeAravisCamera(const CameraParams& params) {
  params.validate();
  return std::unique_ptr<Camera>(aravis().make_camera(params));
}

struct FakeGigECamera::State {
  const detail::AravisPlugin& plugin;
  detail::FakeGigEServer* server;
  std::string address;
};

FakeGigECamera::FakeGigECamera(const FakeCameraParams& params) {
  const detail::AravisPlugin& plugin = aravis();
  state_.reset(new State{plugin, plugin.start_fake(params), params.address});
}

FakeGigECamera::~FakeGigECamera() { state_->plugin.stop_fake(state_->server); }

void FakeGigECamera::serve(const cv::Mat& image) { state_->plugin.serve(*state_->server, image); }

std::string FakeGigECamera::id() const { return state_->address; }

void FakeGigECamera::setPacketLoss(double ratio, unsigned seed) {
  state_->plugin.set_packet_loss(*state_->server, ratio, seed);
}

void FakeGigECamera::suspend() { state_->plugin.suspend(*state_->server); }

void FakeGigECamera::resume() { state_->plugin.resume(*state_->server); }

}  // namespace binpick::acquisition
