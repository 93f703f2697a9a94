// Live-path options: the camera, the projector trigger and the sequencer, parsed once for every
// command that captures.
#include "live_capture.hpp"

#include <memory>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/acquisition/fake_gige_camera.hpp"
#include "binpick/acquisition/sequencer.hpp"
#include "binpick/core/error.hpp"
#include "camera_options.hpp"

namespace binpick::cli {
namespace {

using namespace binpick::acquisition;

SequencerParams sequencerParams(const Arguments& args) {
  SequencerParams params;
  params.settle_us = args.integer("--settle-us").value_or(params.settle_us);
  params.frame_timeout_ms = args.integer("--timeout-ms").value_or(params.frame_timeout_ms);
  params.max_retries = args.integer("--retries").value_or(params.max_retries);
  params.validate();
  return params;
}

// "none" or "gpio:CHIP:LINE".
std::unique_ptr<ProjectorTrigger> projectorTrigger(const Arguments& args) {
  const std::string trigger = args.value("--trigger").value_or("none");
  if (trigger == "none") return makeFreeRunningProjector();
  const auto first = trigger.find(':');
  const auto last = trigger.rfind(':');
  if (trigger.rfind("gpio:", 0) != 0 || first == last) {
    throw core::Error("--trigger needs none or gpio:CHIP:LINE, not '" + trigger + "'");
  }
  GpioTriggerParams params;
  params.chip = trigger.substr(first + 1, last - first - 1);
  const int line = parseInteger("--trigger line", trigger.substr(last + 1));
  if (line < 0) throw core::Error("--trigger line must not be negative (got " + std::to_string(line) + ")");
  params.line = static_cast<unsigned>(line);
  params.pulse_us = args.integer("--pulse-us").value_or(params.pulse_us);
  params.validate();
  return makeGpioTrigger(params);
}

io::Capture captureOnce(Camera& camera, ProjectorTrigger& projector, const Arguments& args,
                        const io::PatternSetSpec& patterns) {
  CaptureSequencer sequencer(camera, projector, sequencerParams(args));
  camera.open();
  camera.start();
  io::Capture capture = sequencer.capture(patterns);  // logs the time and every retry
  camera.stop();
  camera.close();
  return capture;
}

}  // namespace

std::vector<CLI::Option*> addLiveCaptureOptions(CLI::App& command, const std::string& fake_help) {
  CLI::Option* fake = addText(command, "--fake-camera", "DIR", fake_help);
  CLI::Option_group& camera_group = addCameraOptions(command);
  CLI::Option* camera = camera_group.get_option("--camera");
  camera->excludes(fake);
  camera_group.get_option("--pixel-format")->needs(camera);

  CLI::Option_group& live = *command.add_option_group("Live capture options");
  const std::vector<CLI::Option*> real_camera_only = {
      addText(live, "--trigger", "SOURCE", "Projector trigger: none (default, free-running) or gpio:CHIP:LINE"),
      addInteger(live, "--pulse-us", "US", "GPIO trigger pulse in microseconds (default 100)"),
      addText(live, "--projector", "WxH", "Projector resolution for the patterns (default 1280x800)"),
      addInteger(live, "--phase-steps", "N", "Phase-shift images per coded axis (default 4; 0: none)")};
  for (CLI::Option* option : real_camera_only) option->needs(camera);
  addInteger(live, "--settle-us", "US", "Wait after each pattern before the exposure (default 2000)");
  addInteger(live, "--timeout-ms", "MS", "Wait for a frame at most this long (default 1000)");
  addInteger(live, "--retries", "N", "Extra triggers for a pattern whose frame was lost (default 2)");

  std::vector<CLI::Option*> all = {fake};
  for (CLI::App* group : {static_cast<CLI::App*>(&camera_group), static_cast<CLI::App*>(&live)}) {
    for (CLI::Option* option : optionsOf(*group)) all.push_back(option);
  }
  return all;
}

// "1280x800" -> the projector's size in the pattern set.
io::PatternSetSpec patternSetFromArguments(const Arguments& args) {
  io::PatternSetSpec spec;
  if (const auto size = args.value("--projector")) {
    const auto x = size->find('x');
    if (x == std::string::npos) throw core::Error("--projector needs WIDTHxHEIGHT, not '" + *size + "'");
    spec.projector_width = parseInteger("--projector width", size->substr(0, x));
    spec.projector_height = parseInteger("--projector height", size->substr(x + 1));
  }
  spec.phase_steps = args.integer("--phase-steps").value_or(spec.phase_steps);
  spec.row_codes = !(args.declares("--no-rows") && args.flag("--no-rows"));
  spec.validate();
  return spec;
}

io::Capture captureFromCamera(const Arguments& args, const io::PatternSetSpec& patterns) {
  const auto camera = makeAravisCamera(cameraParamsFromArguments(args));
  const auto projector = projectorTrigger(args);
  return captureOnce(*camera, *projector, args, patterns);
}

io::Capture captureFromFake(const Arguments& args, const io::Capture& recorded) {
  FakeCameraParams fake;
  fake.width = recorded.metadata.image_width;
  fake.height = recorded.metadata.image_height;
  fake.sixteen_bit = recorded.metadata.bit_depth == 16;
  FakeGigECamera server(fake);
  CameraParams camera_params = cameraParamsFromArguments(args);
  camera_params.id = server.id();
  camera_params.pixel_format = fake.sixteen_bit ? "Mono16" : "Mono8";
  const auto camera = makeAravisCamera(camera_params);
  const auto projector = makeVirtualProjector(server, recorded.images);
  return captureOnce(*camera, *projector, args, recorded.metadata.pattern_set);
}

}  // namespace binpick::cli
