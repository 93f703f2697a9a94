// binpick detect --model MODEL (--scene CLOUD | --capture DIR): `binpick detect --help`.
// With --capture, the pattern images are reconstructed first (the config file's
// `reconstruction:` section applies): one command from images to poses.
#include <fstream>
#include <iostream>

#include "arguments.hpp"
#include "binpick/core/error.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/estimation/result_json.hpp"
#include "capture_reconstruction.hpp"
#include "commands.hpp"

namespace binpick::cli {
namespace {

estimation::EstimationConfig configFrom(const Arguments& args) {
  estimation::EstimationConfig config;
  if (const auto path = args.value("--config")) config = estimation::loadEstimationConfig(*path);
  for (const std::string& warning : config.warnings) std::cerr << "binpick detect: warning: " << warning << "\n";
  if (const auto n = args.integer("--max-objects")) config.detector.selection.max_objects = *n;
  if (const auto n = args.integer("--threads")) config.detector.threads = *n;
  if (const auto m = args.value("--method")) config.detector.method = estimation::methodFromName(*m);
  config.detector.validate();
  return config;
}

estimation::PreparedModel modelFrom(const Arguments& args, const estimation::ModelParams& params) {
  const std::string path = args.required("--model");
  if (const auto cache = args.value("--model-cache")) return estimation::loadOrPrepareModel(path, params, *cache);
  return estimation::prepareModel(io::readModelGeometry(path), params);
}

void writeOutput(const Arguments& args, const std::string& text) {
  const auto out = args.value("--out");
  if (!out) {
    std::cout << text << "\n";
    return;
  }
  std::ofstream file(*out);
  file << text << "\n";
  if (!file) throw core::Error(*out + ": cannot write the result");
}

// The scene: a point cloud file, or the cloud reconstructed from a capture directory.
io::PointCloud sceneFrom(const Arguments& args) {
  const auto scene = args.value("--scene");
  const auto capture = args.value("--capture");
  if (scene) return io::readPointCloud(*scene);
  CaptureInput input;
  input.capture_dir = *capture;
  input.calibration = args.value("--calib");
  input.config = args.value("--config");
  input.threads = args.integer("--threads");
  return reconstructCaptureDirectory(input).cloud;
}

int run(const Arguments& args) {
  if (!args.value("--scene") && !args.value("--capture")) throw missingOption("--scene or --capture");
  const estimation::EstimationConfig config = configFrom(args);
  const estimation::Detector detector(modelFrom(args, config.model), config.detector);
  const io::PointCloud scene = sceneFrom(args);
  if (!config.detector.scene.crop) {
    // Planar faces of the parts fit the bin's floor and walls anywhere: a bin needs its inside.
    std::cerr << "binpick detect: note: no crop box (detection.scene.crop in --config): the bin's floor and walls "
                 "are matched too; config/virtual-cell.yaml has the virtual cell's bin\n";
  }
  const estimation::DetectionResult result = detector.detect(scene);
  const std::string warning = estimation::sceneWarning(result);
  if (!warning.empty()) std::cerr << "binpick detect: warning: " << warning << "\n";
  writeOutput(args, estimation::toJson(result).dump(2));
  return 0;
}

}  // namespace

void addDetectCommand(CLI::App& program, CommandTable& table) {
  CLI::App& command = table.add(program, "detect", "Find every part's 6-DoF pose in a scene cloud or a capture", run);
  addText(command, "--model", "MODEL", "The part's model: a mesh or cloud file, metres, in the model frame")
      ->required();
  auto* scene = addText(command, "--scene", "CLOUD", "The scene: a point cloud file (.ply, .pcd)");
  auto* capture = addText(command, "--capture", "DIR",
                          "The scene: a capture directory, reconstructed first (docs/capture-format.md)");
  scene->excludes(capture);
  addText(command, "--calib", "FILE", "The rig calibration for --capture (default: the capture's calib.yaml)")
      ->needs(capture);
  addInteger(command, "--max-objects", "N", "Stop after N detections (default: the settings', 20)");
  addText(command, "--config", "FILE",
          "Estimation settings (config/detection.yaml); its reconstruction: section applies to --capture");
  addText(command, "--out", "FILE", "Write the result JSON here (default: stdout)");
  addText(command, "--model-cache", "FILE", "Load the prepared model from FILE, or prepare it and write it there");
  addInteger(command, "--threads", "N", "Threads (default 0: all cores)");
  addText(command, "--method", "NAME", "li_hashimoto (the default) or drost");
}

}  // namespace binpick::cli
