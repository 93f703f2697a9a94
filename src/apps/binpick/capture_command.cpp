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
#include <memory>

#include "arguments.hpp"
#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/acquisition/fake_gige_camera.hpp"
#include "binpick/acquisition/sequencer.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/error.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;
using namespace binpick::acquisition;

CameraParams cameraParams(const Arguments& args) {
  CameraParams params;
  params.id = args.value("--camera").value_or("");
  params.pixel_format = args.value("--pixel-format").value_or(params.pixel_format);
  params.exposure_us = args.number("--exposure-us").value_or(params.exposure_us);
  params.gain_db = args.number("--gain-db").value_or(params.gain_db);
  params.validate();
  return params;
}

SequencerParams sequencerParams(const Arguments& args) {
  SequencerParams params;
  params.settle_us = args.integer("--settle-us").value_or(params.settle_us);
  params.frame_timeout_ms = args.integer("--timeout-ms").value_or(params.frame_timeout_ms);
  params.max_retries = args.integer("--retries").value_or(params.max_retries);
  params.validate();
  return params;
}

// "1280x800" -> the projector's size in the pattern set.
PatternSetSpec patternSet(const Arguments& args) {
  PatternSetSpec spec;
  if (const auto size = args.value("--projector")) {
    const auto x = size->find('x');
    if (x == std::string::npos) throw Error("--projector needs WIDTHxHEIGHT, not '" + *size + "'");
    spec.projector_width = parseInteger("--projector width", size->substr(0, x));
    spec.projector_height = parseInteger("--projector height", size->substr(x + 1));
  }
  spec.phase_steps = args.integer("--phase-steps").value_or(spec.phase_steps);
  spec.row_codes = !args.flag("--no-rows");
  spec.validate();
  return spec;
}

// "none" or "gpio:CHIP:LINE".
std::unique_ptr<ProjectorTrigger> projectorTrigger(const Arguments& args) {
  const std::string trigger = args.value("--trigger").value_or("none");
  if (trigger == "none") return makeFreeRunningProjector();
  const auto first = trigger.find(':');
  const auto last = trigger.rfind(':');
  if (trigger.rfind("gpio:", 0) != 0 || first == last) {
    throw Error("--trigger needs none or gpio:CHIP:LINE, not '" + trigger + "'");
  }
  GpioTriggerParams params;
  params.chip = trigger.substr(first + 1, last - first - 1);
  const int line = parseInteger("--trigger line", trigger.substr(last + 1));
  if (line < 0) throw Error("--trigger line must not be negative (got " + std::to_string(line) + ")");
  params.line = static_cast<unsigned>(line);
  params.pulse_us = args.integer("--pulse-us").value_or(params.pulse_us);
  params.validate();
  return makeGpioTrigger(params);
}

Capture captureOnce(Camera& camera, ProjectorTrigger& projector, const Arguments& args,
                    const PatternSetSpec& patterns) {
  CaptureSequencer sequencer(camera, projector, sequencerParams(args));
  camera.open();
  camera.start();
  Capture capture = sequencer.capture(patterns);  // logs the time and every retry
  camera.stop();
  camera.close();
  return capture;
}

// The live path against a fake camera that serves a recorded capture's images.
Capture captureFromFake(const Arguments& args, const std::string& recorded) {
  const Capture source = readCapture(recorded);
  FakeCameraParams fake;
  fake.width = source.metadata.image_width;
  fake.height = source.metadata.image_height;
  fake.sixteen_bit = source.metadata.bit_depth == 16;
  FakeGigECamera server(fake);
  CameraParams camera_params = cameraParams(args);
  camera_params.id = server.id();
  camera_params.pixel_format = fake.sixteen_bit ? "Mono16" : "Mono8";
  const auto camera = makeAravisCamera(camera_params);
  const auto projector = makeVirtualProjector(server, source.images);
  return captureOnce(*camera, *projector, args, source.metadata.pattern_set);
}

void copyCalibration(const std::optional<std::string>& calibration, const fs::path& out) {
  if (!calibration) return;
  std::error_code error;
  fs::copy_file(*calibration, out / "calib.yaml", error);
  if (error) throw Error(*calibration + ": cannot copy into the capture: " + error.message());
}

}  // namespace

int runCapture(const std::vector<std::string>& raw) {
  const Arguments args(raw,
                       {"--camera", "--fake-camera", "--out", "--pixel-format", "--exposure-us", "--gain-db",
                        "--trigger", "--pulse-us", "--settle-us", "--timeout-ms", "--retries", "--projector",
                        "--phase-steps", "--calib"},
                       {"--no-rows"});
  const fs::path out = args.required("--out");
  const auto fake = args.value("--fake-camera");
  if (fake.has_value() == args.value("--camera").has_value()) throw Error("give either --camera or --fake-camera");
  Capture capture;
  if (fake) {
    capture = captureFromFake(args, *fake);
  } else {
    const auto camera = makeAravisCamera(cameraParams(args));
    const auto projector = projectorTrigger(args);
    capture = captureOnce(*camera, *projector, args, patternSet(args));
  }
  writeCapture(out.string(), std::move(capture));
  // A recording from the fake camera keeps the calibration of the capture it replayed.
  const auto calibration = fake ? std::optional<std::string>((fs::path(*fake) / "calib.yaml").string())
                                : args.value("--calib");
  copyCalibration(calibration, out);
  return 0;
}

}  // namespace binpick::cli
