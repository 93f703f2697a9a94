#pragma once
// The Camera interface on Aravis 0.8 (GigE Vision and USB3 Vision cameras).
#include <memory>

#include "binpick/acquisition/camera.hpp"

namespace binpick::acquisition {

// Does not connect yet: open() does. Throws core::Error on invalid params, or naming the Aravis
// plugin (loaded by the first camera of a process) when it cannot be loaded.
std::unique_ptr<Camera> makeAravisCamera(const CameraParams& params);

}  // namespace binpick::acquisition
