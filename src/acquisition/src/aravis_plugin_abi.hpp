#pragma once
// What the Aravis plugin (plugin/aravis_plugin.cpp) hands to aravis_plugin.cpp: the GigE Vision /
// USB3 Vision camera and the fake GigE Vision camera, behind one table of functions found by a C
// name (binpick/core/plugin.hpp). Only the plugin links Aravis and, through it, GLib, GIO,
// libxml2, libusb and ICU: 16 libraries whose loading (2.1 ms) every start of every program paid
// before, `binpick detect` on a cloud file included, which has no camera. Both sides compile this
// header in the same build; the version refuses a plugin left from another build.
#include <opencv2/core.hpp>

#include "binpick/acquisition/camera.hpp"
#include "binpick/acquisition/fake_gige_camera.hpp"

namespace binpick::acquisition::detail {

inline constexpr int kAravisPluginVersion = 1;
inline constexpr const char* kAravisPluginEntry = "binpick_aravis";

class FakeGigEServer;  // the plugin's (plugin/fake_gige_server.hpp)

// Each function throws what the public function it stands behind documents (core::Error).
struct AravisPlugin {
  int version;
  Camera* (*make_camera)(const CameraParams& params);  // params already validated
  FakeGigEServer* (*start_fake)(const FakeCameraParams& params);
  void (*stop_fake)(FakeGigEServer* fake);
  void (*serve)(FakeGigEServer& fake, const cv::Mat& image);
  void (*set_packet_loss)(FakeGigEServer& fake, double ratio, unsigned seed);
  void (*suspend)(FakeGigEServer& fake);
  void (*resume)(FakeGigEServer& fake);
};

}  // namespace binpick::acquisition::detail

extern "C" const binpick::acquisition::detail::AravisPlugin* binpick_aravis();
