// writePileTruth / readPileTruth: the pile's ground truth beside its capture.
#include "binpick/simulation/pile_truth.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "binpick/core/error.hpp"
#include "binpick/core/json_fields.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::simulation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json objectsJson(const PileScene& scene, const std::string& part_name) {
  json objects = json::array();
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectTruth& o = scene.objects[i];
    objects.push_back({{"id", i},
                       {"pose", core::poseRows(o.T_camera_object)},
                       {"visible_pixels", o.visible_pixels},
                       {"unoccluded_pixels", o.unoccluded_pixels},
                       {"visible_fraction", o.visible_fraction}});
  }
  return {
      {"part", part_name}, {"units", "m"}, {"T_camera_bin", core::poseRows(scene.T_camera_bin)}, {"objects", objects}};
}

// 16-bit labels: 0 nothing, 1 the bin, 2 + i object i (instance ids: -1, -2, i).
cv::Mat maskImage(const PileScene& scene) {
  cv::Mat mask(scene.cloud.height, scene.cloud.width, CV_16UC1);
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      const int32_t id = scene.instance[static_cast<std::size_t>(row) * mask.cols + col];
      const int label = id >= 0 ? std::min(id + 2, 65535) : (id == -1 ? 0 : 1);
      mask.at<uint16_t>(row, col) = static_cast<uint16_t>(label);
    }
  }
  return mask;
}

}  // namespace

void writePileTruth(const std::string& capture_directory, const PileScene& scene, const std::string& part_name,
                    const io::TriangleMesh& part) {
  const fs::path truth = fs::path(capture_directory) / "truth";
  std::error_code error;
  fs::create_directories(truth, error);
  if (error) throw core::Error(truth.string() + ": cannot create: " + error.message());
  std::ofstream objects(truth / "objects.json");
  objects << objectsJson(scene, part_name).dump(2) << "\n";
  if (!objects) throw core::Error((truth / "objects.json").string() + ": cannot write");
  cv::Mat depth(scene.cloud.height, scene.cloud.width, CV_32FC1, const_cast<float*>(scene.depth.data()));
  io::writeImageFile((truth / "depth.tiff").string(), depth);
  io::writeImageFile((truth / "mask.png").string(), maskImage(scene));
  io::writePointCloud((truth / "cloud.ply").string(), scene.exact_cloud);
  io::writeMesh((truth / "part.ply").string(), part);
}

PileTruth readPileTruth(const std::string& path) {
  const fs::path file = fs::is_directory(path) ? fs::path(path) / "truth" / "objects.json" : fs::path(path);
  const json document = core::readJsonFile(file.string());
  PileTruth truth;
  try {
    truth.part = document.at("part").get<std::string>();
    truth.T_camera_bin = core::poseFromRows(document.at("T_camera_bin"), file.string(), "T_camera_bin");
    for (const json& o : document.at("objects")) {
      ObjectTruth object;
      object.T_camera_object = core::poseFromRows(o.at("pose"), file.string(), "pose");
      object.visible_pixels = o.at("visible_pixels").get<int>();
      object.unoccluded_pixels = o.at("unoccluded_pixels").get<int>();
      object.visible_fraction = o.at("visible_fraction").get<double>();
      truth.objects.push_back(object);
    }
  } catch (const json::exception& e) {
    throw core::Error(file.string() + ": malformed truth: " + e.what());
  }
  return truth;
}

}  // namespace binpick::simulation
