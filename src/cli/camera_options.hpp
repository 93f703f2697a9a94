#pragma once
// The camera on the command line, shared by the commands that take images with it, in the option
// group "Camera options":
//   --camera ID  --pixel-format Mono8|Mono10|Mono12|Mono16  --exposure-us E  --gain-db G
// --camera is the device id, serial number or IP address ("" takes the first camera found).
#include <CLI/CLI.hpp>

#include "arguments.hpp"
#include "binpick/acquisition/camera.hpp"

namespace binpick::cli {

// Declares the options above on `command`; returns their group.
CLI::Option_group& addCameraOptions(CLI::App& command);

// The camera the options describe, validated; throws core::Error naming the bad field.
acquisition::CameraParams cameraParamsFromArguments(const Arguments& args);

}  // namespace binpick::cli
