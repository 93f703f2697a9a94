// Calibration import options: parsed once for every command that reads another tool's calibration.
#include "opencv_calibration_options.hpp"

#include "binpick/core/error.hpp"

namespace binpick::cli {
namespace {

std::string roleList() {
  std::string roles;
  for (const std::string& role : io::openCvCalibrationRoles()) roles += (roles.empty() ? "" : ", ") + role;
  return roles;
}

// "projector_matrix=K_proj" -> keys["projector_matrix"] = "K_proj".
void parseKey(const std::string& text, io::OpenCvCalibrationOptions& options) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw core::Error("--key needs ROLE=NAME, e.g. projector_matrix=K2 (got '" + text + "')");
  }
  const std::string role = text.substr(0, equals);
  if (options.keys.count(role) != 0) throw core::Error("--key " + role + " is given twice");
  options.keys[role] = text.substr(equals + 1);
}

}  // namespace

CLI::Option_group& addOpenCvCalibrationOptions(CLI::App& command) {
  CLI::Option_group& group = *command.add_option_group("Calibration import options");
  addText(group, "--units", "mm|m", "Unit of the file's translation (default mm; tools use the board's unit)");
  addText(group, "--camera", "WxH", "Camera image size, when the file has none (img_shape, imageSize, ...)");
  addText(group, "--key", "ROLE=NAME",
          "The file's key for a role, repeatable (default: common names tried). Roles: " + roleList() +
              "; a distortion role may be =none")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return group;
}

ImageSizeArgument parseImageSize(const std::string& option, const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw core::Error(option + " needs WIDTHxHEIGHT, e.g. 1920x1080 (got '" + text + "')");
  return {parseInteger(option + " width", text.substr(0, x)), parseInteger(option + " height", text.substr(x + 1))};
}

io::OpenCvCalibrationOptions openCvCalibrationOptionsFromArguments(const Arguments& args) {
  io::OpenCvCalibrationOptions options;
  if (const auto units = args.value("--units")) {
    try {
      options.units = io::lengthUnitFromName(*units);
    } catch (const core::Error& e) {
      throw core::Error(std::string("--units: ") + e.what());
    }
  }
  if (const auto size = args.value("--camera")) {
    const ImageSizeArgument camera = parseImageSize("--camera", *size);
    options.camera_width = camera.width;
    options.camera_height = camera.height;
  }
  if (args.declares("--projector")) {
    if (const auto size = args.value("--projector")) {
      const ImageSizeArgument projector = parseImageSize("--projector", *size);
      options.projector_width = projector.width;
      options.projector_height = projector.height;
    }
  }
  for (const std::string& key : args.values("--key")) parseKey(key, options);
  try {
    options.validate();
  } catch (const core::Error& e) {
    throw core::Error(std::string("calibration import options: ") + e.what());
  }
  return options;
}

}  // namespace binpick::cli
