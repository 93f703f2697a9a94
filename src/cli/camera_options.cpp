// Camera options: parsed the same way by every command that drives the camera.
#include "camera_options.hpp"

namespace binpick::cli {

const std::set<std::string>& cameraOptionNames() {
  static const std::set<std::string> names = {"--camera", "--pixel-format", "--exposure-us", "--gain-db"};
  return names;
}

acquisition::CameraParams cameraParamsFromArguments(const Arguments& args) {
  acquisition::CameraParams params;
  params.id = args.value("--camera").value_or("");
  params.pixel_format = args.value("--pixel-format").value_or(params.pixel_format);
  params.exposure_us = args.number("--exposure-us").value_or(params.exposure_us);
  params.gain_db = args.number("--gain-db").value_or(params.gain_db);
  params.validate();
  return params;
}

}  // namespace binpick::cli
