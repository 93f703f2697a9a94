#pragma once
// The camera on the command line, shared by the commands that take images with it:
//   --camera ID  --pixel-format Mono8|Mono10|Mono12|Mono16  --exposure-us E  --gain-db G
// --camera is the device id, serial number or IP address ("" takes the first camera found).
#include <set>
#include <string>

#include "arguments.hpp"
#include "binpick/acquisition/camera.hpp"

namespace binpick::cli {

// The valued options above, to merge into a command's own set.
const std::set<std::string>& cameraOptionNames();

// The camera the options describe, validated; throws core::Error naming the bad field.
acquisition::CameraParams cameraParamsFromArguments(const Arguments& args);

}  // namespace binpick::cli
