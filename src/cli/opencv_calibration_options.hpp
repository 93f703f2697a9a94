#pragma once
// Reading another tool's calibration file on the command line (io/opencv_calibration.hpp), shared
// by the commands that take one, in the option group "Calibration import options":
//   --units mm|m  --camera WxH  --key ROLE=NAME (repeatable)
// The file itself (--opencv-calib) and the projector's size (--projector WxH) are the command's
// own options: a command may use them for more than the calibration.
#include <CLI/CLI.hpp>
#include <string>

#include "arguments.hpp"
#include "binpick/io/opencv_calibration.hpp"

namespace binpick::cli {

// Declares the options above on `command`; returns their group.
CLI::Option_group& addOpenCvCalibrationOptions(CLI::App& command);

// The options given, and --projector when the command declares it; throws core::Error naming
// the option on a malformed value or an unknown role.
io::OpenCvCalibrationOptions openCvCalibrationOptionsFromArguments(const Arguments& args);

struct ImageSizeArgument {
  int width = 0, height = 0;
};
// "1920x1080"; throws core::Error naming `option` otherwise.
ImageSizeArgument parseImageSize(const std::string& option, const std::string& text);

}  // namespace binpick::cli
