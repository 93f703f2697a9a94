#pragma once
// Internal to the Aravis plugin: the Camera interface on one Aravis camera (GigE Vision or USB3
// Vision). Does not connect yet: open() does.
#include "binpick/acquisition/camera.hpp"

namespace binpick::acquisition::detail {

Camera* newAravisCamera(const CameraParams& params);  // params already validated; the caller owns it

}  // namespace binpick::acquisition::detail
