#include "binpick/estimation/config.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <sstream>

#include "binpick/io/error.hpp"

namespace binpick::estimation {
namespace {

// One YAML mapping being read: remembers which keys were used so that typos are reported.
class Section {
 public:
  Section(const YAML::Node& node, std::string path, const std::string& origin)
      : node_(node), path_(std::move(path)), origin_(origin) {
    if (node_ && !node_.IsNull() && !node_.IsMap()) fail(path_, "must be a mapping");
  }

  template <class T>
  void read(const char* key, T& value) {
    used_.insert(key);
    if (!node_ || !node_[key]) return;
    try {
      value = node_[key].as<T>();
    } catch (const YAML::Exception&) {
      fail(path_ + key, "has the wrong type");
    }
  }
  Section child(const char* key) {
    used_.insert(key);
    return Section(node_ ? node_[key] : YAML::Node(), path_ + key + ".", origin_);
  }
  bool has(const char* key) const { return node_ && node_[key]; }
  const YAML::Node& node() const { return node_; }

  // Every key of the mapping must have been read.
  void finish() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (!used_.count(key)) fail(path_ + key, "is not a known setting");
    }
  }
  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw Error(origin_ + ": " + key + " " + why);
  }

 private:
  YAML::Node node_;
  std::string path_;
  const std::string& origin_;
  std::set<std::string> used_;
};

Eigen::Vector3f vector3(Section& section, const char* key) {
  std::vector<float> values;
  section.read(key, values);
  if (values.size() != 3) section.fail(key, "needs three numbers");
  return Eigen::Vector3f(values[0], values[1], values[2]);
}

void readModel(Section s, ModelParams& p) {
  s.read("sampling_ratio", p.sampling_ratio);
  s.read("angle_step_deg", p.angle_step_deg);
  s.read("dense_samples_per_step2", p.dense_samples_per_step2);
  s.read("normal_radius_ratio", p.normal_radius_ratio);
  s.read("normal_cluster_angle_deg", p.normal_cluster_angle_deg);
  s.read("max_pairs_per_feature", p.max_pairs_per_feature);
  s.read("seed", p.seed);
  s.finish();
}

void readCrop(Section s, SceneParams& p) {
  if (!s.node() || s.node().IsNull()) return;
  CropBox box;
  box.T_camera_box.translation() = vector3(s, "centre");
  box.half_extents = vector3(s, "half_extents");
  if (s.has("rotation_rpy_deg")) {
    const Eigen::Vector3f rpy = vector3(s, "rotation_rpy_deg") * static_cast<float>(M_PI / 180.0);
    box.T_camera_box.linear() = (Eigen::AngleAxisf(rpy.z(), Eigen::Vector3f::UnitZ()) *
                                 Eigen::AngleAxisf(rpy.y(), Eigen::Vector3f::UnitY()) *
                                 Eigen::AngleAxisf(rpy.x(), Eigen::Vector3f::UnitX())).toRotationMatrix();
  }
  s.finish();
  p.crop = box;
}

void readDetector(Section s, DetectorParams& p) {
  std::string method = methodName(p.method);
  s.read("method", method);
  p.method = methodFromName(method);
  s.read("threads", p.threads);
  Section scene = s.child("scene");
  readCrop(scene.child("crop"), p.scene);
  scene.read("min_normal_neighbours", p.scene.min_normal_neighbours);
  scene.read("max_window_half_size", p.scene.max_window_half_size);
  scene.finish();
  Section voting = s.child("voting");
  voting.read("reference_fraction", p.voting.reference_fraction);
  voting.read("referred_fraction", p.voting.referred_fraction);
  voting.read("poses_per_reference", p.voting.poses_per_reference);
  voting.read("min_relative_votes", p.voting.min_relative_votes);
  voting.read("seed", p.voting.seed);
  voting.finish();
  Section verification = s.child("verification");
  verification.read("voxel_size_ratio", p.verification.voxel_size_ratio);
  verification.read("max_normal_angle_deg", p.verification.max_normal_angle_deg);
  verification.finish();
  Section selection = s.child("selection");
  selection.read("max_objects", p.selection.max_objects);
  selection.read("min_score_fraction", p.selection.min_score_fraction);
  selection.read("min_centre_distance_ratio", p.selection.min_centre_distance_ratio);
  selection.finish();
  Section icp = s.child("icp");
  icp.read("max_iterations", p.icp.max_iterations);
  icp.read("initial_max_distance_ratio", p.icp.initial_max_distance_ratio);
  icp.read("final_max_distance_ratio", p.icp.final_max_distance_ratio);
  icp.read("huber_ratio", p.icp.huber_ratio);
  icp.read("convergence_translation_ratio", p.icp.convergence_translation_ratio);
  icp.read("convergence_rotation_deg", p.icp.convergence_rotation_deg);
  icp.read("fit_distance_ratio", p.icp.fit_distance_ratio);
  icp.read("visible_points_only", p.icp.visible_points_only);
  icp.finish();
  Section clustering = s.child("clustering");
  clustering.read("max_translation_ratio", p.clustering.max_translation_ratio);
  clustering.read("max_rotation_deg", p.clustering.max_rotation_deg);
  clustering.finish();
  s.finish();
}

}  // namespace

EstimationConfig parseEstimationConfig(const std::string& yaml_text, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw Error(origin + ": not valid YAML (line " + std::to_string(e.mark.line + 1) + "): " + e.msg);
  }
  EstimationConfig config;
  Section top(root, "", origin);
  readModel(top.child("model"), config.model);
  readDetector(top.child("detection"), config.detector);
  top.finish();
  try {
    config.model.validate();
    config.detector.validate();
  } catch (const Error& e) {
    throw Error(origin + ": " + e.what());
  }
  return config;
}

EstimationConfig loadEstimationConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the configuration file");
  std::stringstream text;
  text << in.rdbuf();
  return parseEstimationConfig(text.str(), path);
}

}  // namespace binpick::estimation
