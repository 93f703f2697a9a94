// Estimation settings from YAML and the result's JSON schema.
#include <gtest/gtest.h>

#include "binpick/core/error.hpp"
#include "binpick/estimation/config.hpp"
#include "binpick/estimation/result_json.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

TEST(EstimationConfig, ShippedDefaultsFileMatchesTheCodeDefaults) {
  const EstimationConfig shipped = loadEstimationConfig(BINPICK_SOURCE_DIR "/config/detection.yaml");
  const ModelParams m;
  EXPECT_EQ(shipped.model.sampling_ratio, m.sampling_ratio);
  EXPECT_EQ(shipped.model.angle_step_deg, m.angle_step_deg);
  EXPECT_EQ(shipped.model.dense_samples_per_step2, m.dense_samples_per_step2);
  EXPECT_EQ(shipped.model.normal_radius_ratio, m.normal_radius_ratio);
  EXPECT_EQ(shipped.model.normal_cluster_angle_deg, m.normal_cluster_angle_deg);
  EXPECT_EQ(shipped.model.max_pairs_per_feature, m.max_pairs_per_feature);
  const DetectorParams d;
  const DetectorParams& s = shipped.detector;
  EXPECT_EQ(s.method, d.method);
  EXPECT_FALSE(s.scene.crop.has_value());
  EXPECT_EQ(s.voting.reference_fraction, d.voting.reference_fraction);
  EXPECT_EQ(s.voting.referred_fraction, d.voting.referred_fraction);
  EXPECT_EQ(s.voting.poses_per_reference, d.voting.poses_per_reference);
  EXPECT_EQ(s.boundary.enabled, d.boundary.enabled);
  EXPECT_EQ(s.boundary.depth_jump_ratio, d.boundary.depth_jump_ratio);
  EXPECT_EQ(s.boundary.crease_angle_deg, d.boundary.crease_angle_deg);
  EXPECT_EQ(s.boundary.min_linearity, d.boundary.min_linearity);
  EXPECT_EQ(s.verification.voxel_size_ratio, d.verification.voxel_size_ratio);
  EXPECT_EQ(s.verification.max_normal_angle_deg, d.verification.max_normal_angle_deg);
  EXPECT_EQ(s.selection.max_objects, d.selection.max_objects);
  EXPECT_EQ(s.selection.min_score_fraction, d.selection.min_score_fraction);
  EXPECT_EQ(s.selection.min_centre_distance_ratio, d.selection.min_centre_distance_ratio);
  EXPECT_EQ(s.selection.sure_twin_margin, d.selection.sure_twin_margin);
  EXPECT_EQ(s.selection.sure_coverage, d.selection.sure_coverage);
  EXPECT_EQ(s.icp.max_iterations, d.icp.max_iterations);
  EXPECT_EQ(s.icp.final_max_distance_ratio, d.icp.final_max_distance_ratio);
  EXPECT_EQ(s.icp.fit_distance_ratio, d.icp.fit_distance_ratio);
  EXPECT_EQ(s.icp.max_normal_angle_deg, d.icp.max_normal_angle_deg);
  EXPECT_EQ(s.clustering.max_rotation_deg, d.clustering.max_rotation_deg);
}

TEST(EstimationConfig, ReadsCropBoxAndOverrides) {
  const EstimationConfig c = parseEstimationConfig(
      "detection:\n  method: drost\n  selection: {max_objects: 7}\n"
      "  scene:\n    crop:\n      pose: {translation: [0, 0, 0.5], rotation: [0, 0, 90], convention: fixed_xyz}\n"
      "      half_extents: [0.2, 0.1, 0.3]\n"
      "  boundary: {enabled: false, depth_jump_ratio: 2, crease_angle_deg: 45, min_linearity: 5}\n",
      "test.yaml");
  EXPECT_EQ(c.detector.method, Method::Drost);
  EXPECT_FALSE(c.detector.boundary.enabled);
  EXPECT_EQ(c.detector.boundary.depth_jump_ratio, 2.0f);
  EXPECT_EQ(c.detector.boundary.crease_angle_deg, 45.0f);
  EXPECT_EQ(c.detector.boundary.min_linearity, 5.0f);
  EXPECT_EQ(c.detector.selection.max_objects, 7);
  ASSERT_TRUE(c.detector.scene.crop.has_value());
  // A 90-degree yaw swaps the box's x and y extents in the camera frame.
  EXPECT_TRUE(c.detector.scene.crop->contains(Eigen::Vector3f(0.05f, 0.15f, 0.5f)));
  EXPECT_FALSE(c.detector.scene.crop->contains(Eigen::Vector3f(0.15f, 0.05f, 0.5f)));
  EXPECT_TRUE(c.warnings.empty());
}

TEST(EstimationConfig, OlderCropFormIsReadWithAWarningNamingTheNewKey) {
  const EstimationConfig older = parseEstimationConfig(
      "detection:\n  scene:\n    crop: {centre: [0.1, 0, 0.5], half_extents: [0.2, 0.1, 0.3], "
      "rotation_rpy_deg: [10, -20, 90]}\n",
      "cell.yaml");
  const EstimationConfig newer = parseEstimationConfig(
      "detection:\n  scene:\n    crop:\n      pose: {translation: [0.1, 0, 0.5], rotation: [10, -20, 90], "
      "convention: fixed_xyz}\n      half_extents: [0.2, 0.1, 0.3]\n",
      "cell.yaml");
  ASSERT_TRUE(older.detector.scene.crop && newer.detector.scene.crop);
  EXPECT_TRUE(older.detector.scene.crop->T_camera_box.isApprox(newer.detector.scene.crop->T_camera_box, 1e-6f));
  ASSERT_EQ(older.warnings.size(), 1u);
  EXPECT_NE(older.warnings[0].find("cell.yaml: detection.scene.crop"), std::string::npos) << older.warnings[0];
  EXPECT_NE(older.warnings[0].find("pose: {translation"), std::string::npos) << older.warnings[0];
  EXPECT_TRUE(newer.warnings.empty());
}

TEST(EstimationConfig, ErrorsNameTheFileAndTheKey) {
  const auto message = [](const std::string& yaml) {
    return binpick::estimation::testing::errorMessage([&] { parseEstimationConfig(yaml, "cell.yaml"); });
  };
  EXPECT_NE(message("detection:\n  voting:\n    reference_fractoin: 0.2\n")
                .find("cell.yaml: detection.voting.reference_fractoin"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  selection:\n    max_objects: many\n")
                .find("detection.selection.max_objects has the wrong type"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  voting:\n    reference_fraction: 0\n").find("reference_fraction"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  scene:\n    crop: {centre: [0, 0], half_extents: [1, 1, 1]}\n")
                .find("centre needs three numbers"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  scene:\n    crop: {half_extents: [1, 1, 1]}\n")
                .find("detection.scene.crop.pose is required"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  scene:\n    crop: {pose: {translation: [0, 0, .nan]}, half_extents: [1, 1, 1]}\n")
                .find("detection.scene.crop.pose.translation"),
            std::string::npos);
  EXPECT_NE(message("detection:\n  boundary:\n    crease_angle_deg: 0\n").find("crease_angle_deg"), std::string::npos);
  EXPECT_NE(message("detection: [1, 2\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(message("detection:\n  method: magic\n").find("method 'magic' is unknown"), std::string::npos);
  EXPECT_NE(binpick::estimation::testing::errorMessage([] {
              loadEstimationConfig("/no/such/cell.yaml");
            }).find("/no/such/cell.yaml"),
            std::string::npos);
}

TEST(ResultJson, KeepsTheDocumentedSchema) {
  DetectionResult result;
  Detection d;
  d.T_camera_model.translation() = Eigen::Vector3f(0.1f, -0.2f, 0.8f);
  d.score = 0.5f;
  result.detections.push_back(d);
  result.timing_ms.total = 12.5;
  const nlohmann::json j = toJson(result);
  ASSERT_EQ(j.at("detections").size(), 1u);
  const nlohmann::json& pose = j.at("detections")[0].at("pose");
  ASSERT_EQ(pose.size(), 4u);
  EXPECT_FLOAT_EQ(pose[0][3].get<float>(), 0.1f);
  EXPECT_FLOAT_EQ(pose[2][3].get<float>(), 0.8f);
  EXPECT_EQ(pose[3], nlohmann::json({0.0, 0.0, 0.0, 1.0}));
  for (const char* key : {"score", "coverage", "icp_rmse", "votes"})
    EXPECT_TRUE(j["detections"][0].contains(key)) << key;
  for (const char* key : {"prepare_scene", "voting", "verification", "selection", "icp", "total"}) {
    EXPECT_TRUE(j.at("timing_ms").contains(key)) << key;
  }
  EXPECT_DOUBLE_EQ(j["timing_ms"]["total"].get<double>(), 12.5);
}

}  // namespace
}  // namespace binpick::estimation
