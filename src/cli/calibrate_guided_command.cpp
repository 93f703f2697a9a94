// binpick calibrate hand-eye --listen --record DIR --count K (--camera ID ... | --replay DIR)
//     [--port N] [--port-file F] [--idle-timeout-s S] [robot codec options] --calib calib.yaml --setup SETUP
//     [board options] [--method NAME] [--min-views N] [--refine] --out hand_eye.yaml
// The guided hand-eye session: serves the robot protocol until K views are recorded in DIR (the
// robot sends POSE at each taught pose), then runs the file mode on DIR. Ctrl-C or SIGTERM stops
// it keeping every view; running the same command again continues the session.
#include <signal.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>

#include "binpick/acquisition/aravis_camera.hpp"
#include "binpick/calibration/hand_eye.hpp"
#include "binpick/core/error.hpp"
#include "binpick/io/rig_calibration.hpp"
#include "board_options.hpp"
#include "calibrate_hand_eye.hpp"
#include "camera_options.hpp"
#include "commands.hpp"
#include "hand_eye_guided_serving.hpp"
#include "robot_codec_options.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<ViewCamera> viewCameraFrom(const Arguments& args) {
  const auto replay = args.value("--replay");
  if (!replay && !args.value("--camera")) throw missingOption("--camera or --replay");
  if (replay) return makeReplayViewCamera(*replay);
  acquisition::CameraParams camera = cameraParamsFromArguments(args);
  camera.trigger = acquisition::TriggerSource::Software;  // one frame per view, when asked
  return makeLiveViewCamera(acquisition::makeAravisCamera(camera), args.integer("--timeout-ms").value_or(5000));
}

// Everything the session needs, checked before the robot is told to start.
GuidedSessionParams sessionParamsFrom(const Arguments& args) {
  GuidedSessionParams params;
  const auto count = args.integer("--count");
  if (!count) throw missingOption("--count");
  params.wanted = *count;
  params.layout = boardLayoutFromArguments(args);
  params.camera = io::readRigCalibration(args.required("--calib")).camera;
  calibration::handEyeSetupFromName(args.required("--setup"));
  if (const auto method = args.value("--method")) calibration::handEyeMethodFromName(*method);
  const int min_views = args.integer("--min-views").value_or(calibration::HandEyeParams{}.min_views);
  if (params.wanted < min_views) {
    throw core::Error("--count must be at least the views the calibration needs (" + std::to_string(min_views) +
                      ", --min-views), got " + std::to_string(params.wanted));
  }
  const fs::path out = fs::absolute(args.required("--out"));
  if (!fs::is_directory(out.parent_path())) {
    throw core::Error("--out: no directory " + out.parent_path().string());
  }
  params.validate();
  return params;
}

GuidedServerOptions serverOptionsFrom(const Arguments& args) {
  GuidedServerOptions options;
  options.server.port = args.integer("--port").value_or(options.server.port);
  options.server.codec = codecFromArguments(args);
  // A technician walking the robot through taught poses by hand pauses longer than a cycle does.
  if (const auto idle_s = args.integer("--idle-timeout-s")) {
    if (*idle_s < 0 || *idle_s > 86400)
      throw core::Error("--idle-timeout-s must be in [0, 86400] (0: never), got " + std::to_string(*idle_s));
    options.server.idle_timeout_ms = static_cast<int>(*idle_s * 1000);
  }
  options.server.validate();
  options.port_file = args.value("--port-file").value_or("");
  return options;
}

void setStopSignalsBlocked(bool blocked) {
  const sigset_t signals = stopSignals();
  pthread_sigmask(blocked ? SIG_BLOCK : SIG_UNBLOCK, &signals, nullptr);
}

}  // namespace

void addGuidedSessionOptions(CLI::App& hand_eye, CLI::Option* listen) {
  CLI::Option* replay = addText(hand_eye, "--replay", "DIR", "Take the views from DIR's images, in name order");
  std::vector<CLI::Option*> guided = {
      addText(hand_eye, "--record", "DIR", "Record the views here (required; continues a session)"),
      addInteger(hand_eye, "--count", "K", "Views to record (required, at least --min-views)"),
      replay,
      addInteger(hand_eye, "--port", "N", "Robot protocol port (default 50100; 0: any free port)"),
      addText(hand_eye, "--port-file", "FILE", "Write the bound port here once listening"),
      addInteger(hand_eye, "--idle-timeout-s", "S",
                 "Disconnect a robot silent for this long between views (default 600; 0: never)")};
  CLI::Option_group& camera_group = addCameraOptions(hand_eye);
  CLI::Option* camera = camera_group.get_option("--camera");
  camera->excludes(replay);
  guided.push_back(camera);
  // The camera's other options need --camera, and so --listen through it.
  for (CLI::Option* option : optionsOf(camera_group)) {
    if (option != camera) option->needs(camera);
  }
  addInteger(camera_group, "--timeout-ms", "MS", "Wait for a frame at most this long (default 5000)")->needs(camera);
  for (CLI::Option* option : optionsOf(addRobotCodecOptions(hand_eye))) guided.push_back(option);
  for (CLI::Option* option : guided) option->needs(listen);
}

int runGuidedSession(const Arguments& args) {
  const std::string directory = args.required("--record");
  const GuidedSessionParams params = sessionParamsFrom(args);
  const GuidedServerOptions server = serverOptionsFrom(args);
  const std::unique_ptr<ViewCamera> camera = viewCameraFrom(args);
  // Before any thread starts, so that the signals reach the loop waiting for them.
  setStopSignalsBlocked(true);
  GuidedViewRecorder recorder(directory, server.server.codec.orientation);
  if (recorder.accepted() >= params.wanted) {
    spdlog::info("{} already holds {} views: calibrating", directory, recorder.accepted());
  } else if (!serveGuidedSession(params, server, recorder, *camera)) {
    spdlog::error(
        "stopped with {} of {} views recorded in {}; the same command continues the "
        "session",
        recorder.accepted(), params.wanted, directory);
    return 1;
  }
  setStopSignalsBlocked(false);  // the calibration may be interrupted as any command
  return calibrateFromViews(args, directory);
}

}  // namespace binpick::cli
