// Camera options: declared and read the same way by every command that drives the camera.
#include "camera_options.hpp"

namespace binpick::cli {

CLI::Option_group& addCameraOptions(CLI::App& command) {
  CLI::Option_group& group = *command.add_option_group("Camera options");
  addText(group, "--camera", "ID", "GigE Vision camera: device id, serial or IP address");
  addText(group, "--pixel-format", "FORMAT", "Mono8 (default), Mono10, Mono12 or Mono16");
  addNumber(group, "--exposure-us", "US", "Exposure time in microseconds (default 8000)");
  addNumber(group, "--gain-db", "DB", "Gain in dB (default 0)");
  return group;
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
