// binpick capture (--camera ID | --fake-camera CAPTURE_DIR) --out DIR: `binpick capture --help`.
// Records one capture from the live path: the projector shows each pattern (GPIO pulse, or it
// runs on its own with --trigger none), the camera (Aravis) takes one whole frame per pattern, and
// the capture directory is written for replay and reconstruction. --fake-camera serves the images
// of a recorded capture from an in-process GigE Vision camera on 127.0.0.1 behind a virtual
// projector: the same path without hardware, for tests and demos.
#include <filesystem>
#include <optional>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/capture.hpp"
#include "commands.hpp"
#include "live_capture.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

void copyCalibration(const std::optional<std::string>& calibration, const fs::path& out) {
  if (!calibration) return;
  std::error_code error;
  fs::copy_file(*calibration, out / "calib.yaml", error);
  if (error) throw core::Error(*calibration + ": cannot copy into the capture: " + error.message());
}

int run(const Arguments& args) {
  const fs::path out = args.required("--out");
  const auto fake = args.value("--fake-camera");
  if (!fake && !args.value("--camera")) throw missingOption("--camera or --fake-camera");
  io::Capture capture =
      fake ? captureFromFake(args, io::readCapture(*fake)) : captureFromCamera(args, patternSetFromArguments(args));
  io::writeCapture(out.string(), std::move(capture));
  // A recording from the fake camera keeps the calibration of the capture it replayed.
  const auto calibration =
      fake ? std::optional<std::string>((fs::path(*fake) / "calib.yaml").string()) : args.value("--calib");
  copyCalibration(calibration, out);
  return 0;
}

}  // namespace

void addCaptureCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command = table.add(program, "capture", "Record one capture from the camera and the projector", run);
  addText(command, "--out", "DIR", "Write the capture directory here")->required();
  addLiveCaptureOptions(command, "Serve a recorded capture's images from a fake GigE camera on 127.0.0.1");
  CLI::Option* camera = command.get_option("--camera");
  addFlag(command, "--no-rows", "Project column codes only (default: rows too)")->needs(camera);
  addText(command, "--calib", "FILE", "Copy this rig calibration into the capture as calib.yaml")->needs(camera);
}

}  // namespace binpick::cli
