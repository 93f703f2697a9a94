#include "binpick/estimation/config.hpp"

#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/core/orientation.hpp"
#include "binpick/core/pose_yaml.hpp"
#include "binpick/core/yaml_section.hpp"

namespace binpick::estimation {
namespace {

using Section = core::YamlSection;

Eigen::Vector3f vector3(Section& section, const char* key) {
  Eigen::Vector3d value = Eigen::Vector3d::Constant(std::nan(""));
  section.readVector3(key, value);
  if (!value.allFinite()) section.fail(key, "needs three numbers");
  return value.cast<float>();
}

void readModel(Section s, ModelParams& p) {
  s.read("sampling_ratio", p.sampling_ratio);
  s.read("angle_step_deg", p.angle_step_deg);
  s.read("dense_samples_per_step2", p.dense_samples_per_step2);
  s.read("normal_radius_ratio", p.normal_radius_ratio);
  s.read("normal_cluster_angle_deg", p.normal_cluster_angle_deg);
  s.read("max_pairs_per_feature", p.max_pairs_per_feature);
  s.read("seed", p.seed);
  s.read("reduce_by_symmetry", p.reduce_by_symmetry);
  s.finish();
}

// The crop box before it took core's pose form: a centre and roll, pitch, yaw in degrees for
// Rz(yaw) Ry(pitch) Rx(roll), which is core's fixed_xyz convention with the same three values.
Eigen::Isometry3d oldCropPose(Section& s) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = vector3(s, "centre").cast<double>();
  if (s.has("rotation_rpy_deg")) {
    const Eigen::Vector3d rpy = vector3(s, "rotation_rpy_deg").cast<double>();
    pose.linear() = core::rotationFromValues({rpy.x(), rpy.y(), rpy.z()}, core::Orientation::FixedXYZ);
  }
  return pose;
}

// crop: {pose: {translation, rotation, convention} (core's pose form, pose_yaml.hpp), half_extents}.
void readCrop(Section s, SceneParams& p, std::vector<std::string>& warnings) {
  if (s.isNull()) return;
  CropBox box;
  box.half_extents = vector3(s, "half_extents");
  if (s.has("pose")) {
    box.T_camera_box = core::readPose(s.child("pose")).cast<float>();
  } else if (s.has("centre")) {
    box.T_camera_box = oldCropPose(s).cast<float>();
    warnings.push_back(
        "detection.scene.crop: centre and rotation_rpy_deg are an older form, read for now; write "
        "pose: {translation: [x, y, z], rotation: [roll, pitch, yaw], convention: fixed_xyz} instead");
  } else {
    s.fail("pose", "is required: {translation: [x, y, z], rotation: [...], convention: NAME}");
  }
  s.finish();
  p.crop = box;
}

void readDetector(Section s, DetectorParams& p, std::vector<std::string>& warnings) {
  std::string method = methodName(p.method);
  s.read("method", method);
  try {
    p.method = methodFromName(method);
  } catch (const core::Error& e) {
    s.fail("method", e.what());
  }
  s.read("threads", p.threads);
  Section scene = s.child("scene");
  readCrop(scene.child("crop"), p.scene, warnings);
  scene.read("min_normal_neighbours", p.scene.min_normal_neighbours);
  scene.read("max_window_half_size", p.scene.max_window_half_size);
  scene.read("line_of_sight_cell_ratio", p.scene.line_of_sight_cell_ratio);
  scene.finish();
  Section voting = s.child("voting");
  voting.read("reference_fraction", p.voting.reference_fraction);
  voting.read("referred_fraction", p.voting.referred_fraction);
  voting.read("poses_per_reference", p.voting.poses_per_reference);
  voting.read("min_relative_votes", p.voting.min_relative_votes);
  voting.read("seed", p.voting.seed);
  voting.finish();
  Section boundary = s.child("boundary");
  boundary.read("enabled", p.boundary.enabled);
  boundary.read("depth_jump_ratio", p.boundary.depth_jump_ratio);
  boundary.read("crease_angle_deg", p.boundary.crease_angle_deg);
  boundary.read("min_linearity", p.boundary.min_linearity);
  boundary.finish();
  Section verification = s.child("verification");
  verification.read("voxel_size_ratio", p.verification.voxel_size_ratio);
  verification.read("max_normal_angle_deg", p.verification.max_normal_angle_deg);
  verification.read("free_space_tolerance_ratio", p.verification.free_space_tolerance_ratio);
  verification.read("free_space_penalty", p.verification.free_space_penalty);
  verification.read("refined_tolerance_ratio", p.verification.refined_tolerance_ratio);
  verification.read("max_refined_seen_through", p.verification.max_refined_seen_through);
  verification.read("compare_turned", p.verification.compare_turned);
  verification.finish();
  Section selection = s.child("selection");
  selection.read("max_objects", p.selection.max_objects);
  selection.read("min_score_fraction", p.selection.min_score_fraction);
  selection.read("min_coverage", p.selection.min_coverage);
  selection.read("min_centre_distance_ratio", p.selection.min_centre_distance_ratio);
  selection.read("sure_twin_margin", p.selection.sure_twin_margin);
  selection.read("sure_coverage", p.selection.sure_coverage);
  selection.finish();
  Section icp = s.child("icp");
  icp.read("max_iterations", p.icp.max_iterations);
  icp.read("initial_max_distance_ratio", p.icp.initial_max_distance_ratio);
  icp.read("final_max_distance_ratio", p.icp.final_max_distance_ratio);
  icp.read("huber_ratio", p.icp.huber_ratio);
  icp.read("point_weight", p.icp.point_weight);
  icp.read("convergence_translation_ratio", p.icp.convergence_translation_ratio);
  icp.read("convergence_rotation_deg", p.icp.convergence_rotation_deg);
  icp.read("fit_distance_ratio", p.icp.fit_distance_ratio);
  icp.read("max_normal_angle_deg", p.icp.max_normal_angle_deg);
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
  const YAML::Node root = core::parseYaml(yaml_text, origin);
  EstimationConfig config;
  Section top(root, "", origin);
  readModel(top.child("model"), config.model);
  readDetector(top.child("detection"), config.detector, config.warnings);
  for (std::string& warning : config.warnings) warning = origin + ": " + warning;
  top.skip("reconstruction");  // the same cell file configures reconstruction
  top.finish();
  core::validateSettings(origin, [&] {
    config.model.validate();
    config.detector.validate();
  });
  return config;
}

EstimationConfig loadEstimationConfig(const std::string& path) {
  return parseEstimationConfig(core::readConfigFile(path), path);
}

}  // namespace binpick::estimation
