#pragma once
// RAII ownership of Embree handles, and Embree's errors turned into core::Error.
// Internal to binpick::simulation. An EmbreeDevice may be used from several threads; the handles
// are plain owners (move-only, not synchronised).
#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <string>

namespace binpick::simulation::detail {

class EmbreeDevice {
 public:
  // Throws core::Error when Embree cannot create a device (e.g. an unsupported CPU).
  EmbreeDevice();
  ~EmbreeDevice();
  // Embree's error callback keeps a pointer to this object: it must not move.
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

  // Throws core::Error "<context>: Embree error: <message>" when an Embree call made by this
  // thread on this device failed since the last check.
  void throwIfFailed(const std::string& context) const;

 private:
  static void recordError(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::string last_message_;  // guarded by mutex_
};

struct SceneReleaser {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
struct GeometryReleaser {
  void operator()(RTCGeometry geometry) const { rtcReleaseGeometry(geometry); }
};
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneReleaser>;
using GeometryHandle = std::unique_ptr<RTCGeometryTy, GeometryReleaser>;

// A new, empty scene tuned for accurate single-ray queries. Throws core::Error on failure.
SceneHandle newScene(const EmbreeDevice& device);

}  // namespace binpick::simulation::detail
