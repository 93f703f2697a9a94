// binpick detect --model MODEL (--scene CLOUD | --capture DIR [--calib FILE]) [--max-objects N]
//                [--config FILE] [--out FILE] [--model-cache FILE] [--threads N]
//                [--method li_hashimoto|drost]
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
  if (scene.has_value() == capture.has_value()) throw core::Error("give either --scene or --capture");
  if (scene) {
    if (args.value("--calib")) throw core::Error("--calib applies to --capture only");
    return io::readPointCloud(*scene);
  }
  CaptureInput input;
  input.capture_dir = *capture;
  input.calibration = args.value("--calib");
  input.config = args.value("--config");
  input.threads = args.integer("--threads");
  return reconstructCaptureDirectory(input).cloud;
}

}  // namespace

int runDetect(const std::vector<std::string>& raw) {
  const Arguments args(raw,
                       {"--model", "--scene", "--capture", "--calib", "--max-objects", "--config", "--out",
                        "--model-cache", "--threads", "--method"},
                       {});
  const estimation::EstimationConfig config = configFrom(args);
  const estimation::Detector detector(modelFrom(args, config.model), config.detector);
  const io::PointCloud scene = sceneFrom(args);
  const estimation::DetectionResult result = detector.detect(scene);
  writeOutput(args, estimation::toJson(result).dump(2));
  return 0;
}

}  // namespace binpick::cli
