// binpick calibrate hand-eye --listen --record DIR --count K
//     (--camera ID [--pixel-format F] [--exposure-us E] [--gain-db G] [--timeout-ms T]
//      | --replay IMAGES_DIR)
//     [--port N] [--port-file F] [--framing ascii|binary] [--orientation NAME]
//     [--byte-order big|little] --calib calib.yaml --setup eye-to-hand|eye-in-hand
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
#include "camera_options.hpp"
#include "commands.hpp"
#include "hand_eye_guided_serving.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

// Given to the file mode as they are.
const std::set<std::string> kCalibrationOptions = {"--calib", "--setup", "--method", "--min-views", "--out"};

std::set<std::string> optionNames() {
  std::set<std::string> names = {"--record",    "--count",   "--replay",      "--timeout-ms", "--port",
                                 "--port-file", "--framing", "--orientation", "--byte-order"};
  names.insert(kCalibrationOptions.begin(), kCalibrationOptions.end());
  names.insert(boardOptionNames().begin(), boardOptionNames().end());
  names.insert(cameraOptionNames().begin(), cameraOptionNames().end());
  return names;
}

robot::CodecParams codecFrom(const Arguments& args) {
  robot::CodecParams codec;
  codec.framing = robot::framingFromName(args.value("--framing").value_or("ascii"));
  codec.byte_order = robot::byteOrderFromName(args.value("--byte-order").value_or("big"));
  if (const auto name = args.value("--orientation")) {
    codec.orientation = core::orientationFromName(*name);
  }
  codec.validate();
  return codec;
}

std::unique_ptr<ViewCamera> viewCameraFrom(const Arguments& args) {
  const auto replay = args.value("--replay");
  if (replay.has_value() == args.value("--camera").has_value()) {
    throw core::Error("give either --camera or --replay");
  }
  if (replay) return makeReplayViewCamera(*replay);
  acquisition::CameraParams camera = cameraParamsFromArguments(args);
  camera.trigger = acquisition::TriggerSource::Software;  // one frame per view, when asked
  return makeLiveViewCamera(acquisition::makeAravisCamera(camera), args.integer("--timeout-ms").value_or(5000));
}

// Everything the session needs, checked before the robot is told to start.
GuidedSessionParams sessionParamsFrom(const Arguments& args) {
  GuidedSessionParams params;
  params.wanted = parseInteger("--count", args.required("--count"));
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
  options.server.codec = codecFrom(args);
  options.server.validate();
  options.port_file = args.value("--port-file").value_or("");
  return options;
}

// The file mode's arguments: the recorded views and the options it shares with this command.
std::vector<std::string> calibrationArguments(const Arguments& args, const std::string& views) {
  std::vector<std::string> forwarded = {"--views", views};
  std::set<std::string> names = kCalibrationOptions;
  names.insert(boardOptionNames().begin(), boardOptionNames().end());
  for (const std::string& name : names) {
    if (const auto value = args.value(name)) {
      forwarded.push_back(name);
      forwarded.push_back(*value);
    }
  }
  if (args.flag("--refine")) forwarded.push_back("--refine");
  return forwarded;
}

void setStopSignalsBlocked(bool blocked) {
  const sigset_t signals = stopSignals();
  pthread_sigmask(blocked ? SIG_BLOCK : SIG_UNBLOCK, &signals, nullptr);
}

}  // namespace

int runCalibrateHandEyeGuided(const std::vector<std::string>& raw) {
  const Arguments args(raw, optionNames(), {"--listen", "--refine"});
  if (!args.flag("--listen")) throw core::Error("the guided session needs --listen");
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
  return runCalibrateHandEye(calibrationArguments(args, directory));
}

}  // namespace binpick::cli
