// EmbreeDevice: device lifetime and error reporting.
#include "embree_device.hpp"

#include "binpick/core/error.hpp"

namespace binpick::simulation::detail {
namespace {

const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    case RTC_ERROR_UNKNOWN: break;
  }
  return "unknown error";
}

}  // namespace

EmbreeDevice::EmbreeDevice() {
  // Default configuration: Embree sizes its build thread pool itself. Limiting it through the
  // configuration string ("threads=N") would limit every TBB user in the process.
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr) {
    throw core::Error(std::string("RayCaster: Embree could not create a device (") +
                      errorName(rtcGetDeviceError(nullptr)) + ")");
  }
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::recordError, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::recordError(void* self, RTCError code, const char* message) {
  auto* device = static_cast<EmbreeDevice*>(self);
  const std::lock_guard<std::mutex> lock(device->mutex_);
  const std::string name = errorName(code);
  const std::string detail = message ? message : "";
  device->last_message_ = detail.empty() || detail == name ? name : name + ": " + detail;
}

void EmbreeDevice::throwIfFailed(const std::string& context) const {
  const RTCError code = rtcGetDeviceError(device_);  // also clears this thread's error flag
  if (code == RTC_ERROR_NONE) return;
  std::string message;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    message.swap(last_message_);
  }
  if (message.empty()) message = errorName(code);
  throw core::Error(context + ": Embree error: " + message);
}

SceneHandle newScene(const EmbreeDevice& device) {
  SceneHandle scene(rtcNewScene(device.get()));
  device.throwIfFailed("RayCaster: creating a scene");
  if (!scene) throw core::Error("RayCaster: Embree could not create a scene");
  // Robust traversal: no cracks along shared edges, at a small cost in speed. High build
  // quality: the scenes are small, so a better tree costs little to build and saves traversal.
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
  device.throwIfFailed("RayCaster: configuring a scene");
  return scene;
}

}  // namespace binpick::simulation::detail
