// binpick detect --model MODEL --scene SCENE [--max-objects N] [--config FILE] [--out FILE]
//                [--model-cache FILE] [--threads N] [--method li_hashimoto|drost]
#include <fstream>
#include <iostream>

#include "arguments.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/estimation/result_json.hpp"
#include "binpick/io/error.hpp"
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
  return estimation::prepareModel(readModelGeometry(path), params);
}

void writeOutput(const Arguments& args, const std::string& text) {
  const auto out = args.value("--out");
  if (!out) {
    std::cout << text << "\n";
    return;
  }
  std::ofstream file(*out);
  file << text << "\n";
  if (!file) throw Error(*out + ": cannot write the result");
}

}  // namespace

int runDetect(const std::vector<std::string>& raw) {
  const Arguments args(raw, {"--model", "--scene", "--max-objects", "--config", "--out", "--model-cache",
                             "--threads", "--method"},
                       {});
  const estimation::EstimationConfig config = configFrom(args);
  const std::string scene_path = args.required("--scene");
  const estimation::Detector detector(modelFrom(args, config.model), config.detector);
  const PointCloud scene = readPointCloud(scene_path);
  const estimation::DetectionResult result = detector.detect(scene);
  writeOutput(args, estimation::toJson(result).dump(2));
  return 0;
}

}  // namespace binpick::cli
