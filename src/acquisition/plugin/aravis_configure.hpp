#pragma once
// Internal: applying CameraParams to a connected Aravis camera.
#include <arv.h>

#include <string>

#include "binpick/acquisition/camera.hpp"

namespace binpick::acquisition::detail {

// Pixel format, region, exposure, gain, trigger and (GigE Vision) packet size, in the order
// cameras need them (the format before the region: width increments depend on it). Throws
// core::Error "NAME: cannot set FIELD to VALUE: WHAT ARAVIS SAID" on the first refusal.
void configureCamera(ArvCamera* camera, const CameraParams& params, const std::string& name);

}  // namespace binpick::acquisition::detail
