// binpick capture (--camera ID | --fake-camera CAPTURE_DIR) --out DIR
//                 [--pixel-format Mono8|Mono10|Mono12|Mono16] [--exposure-us E] [--gain-db G]
//                 [--trigger none|gpio:CHIP:LINE] [--pulse-us P] [--settle-us S] [--timeout-ms T]
//                 [--retries R] [--projector WIDTHxHEIGHT] [--phase-steps N] [--no-rows]
//                 [--calib FILE]
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

}  // namespace

int runCapture(const std::vector<std::string>& raw) {
  std::set<std::string> valued = liveCaptureOptionNames();
  valued.insert({"--out", "--calib"});
  const Arguments args(raw, valued, {"--no-rows"});
  const fs::path out = args.required("--out");
  const auto fake = args.value("--fake-camera");
  if (fake.has_value() == args.value("--camera").has_value())
    throw core::Error("give either --camera or --fake-camera");
  io::Capture capture =
      fake ? captureFromFake(args, io::readCapture(*fake)) : captureFromCamera(args, patternSetFromArguments(args));
  io::writeCapture(out.string(), std::move(capture));
  // A recording from the fake camera keeps the calibration of the capture it replayed.
  const auto calibration =
      fake ? std::optional<std::string>((fs::path(*fake) / "calib.yaml").string()) : args.value("--calib");
  copyCalibration(calibration, out);
  return 0;
}

}  // namespace binpick::cli
