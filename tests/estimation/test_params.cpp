// Parameter validation and bad or empty inputs: errors name the field, expected outcomes are values.
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "binpick/estimation/detector.hpp"
#include "estimation_test_support.hpp"
#include "scene.hpp"
#include "voting.hpp"

namespace binpick::estimation {
namespace {

using testing::errorMessage;
using testing::smallModel;

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// Applies `change` to default params and expects validate() to throw naming `field`.
template <class Params>
void expectRejected(const std::string& field, const std::function<void(Params&)>& change) {
  Params p;
  EXPECT_NO_THROW(p.validate()) << "defaults must be valid";
  change(p);
  const std::string message = errorMessage([&] { p.validate(); });
  EXPECT_NE(message.find(field), std::string::npos) << "message '" << message << "' does not name " << field;
}

TEST(Params, ModelParamsNameTheField) {
  using P = ModelParams;
  expectRejected<P>("sampling_ratio", [](P& p) { p.sampling_ratio = 0.0f; });
  expectRejected<P>("sampling_ratio", [](P& p) { p.sampling_ratio = kNaN; });
  expectRejected<P>("sampling_ratio", [](P& p) { p.sampling_ratio = 2.0f; });
  expectRejected<P>("angle_step_deg", [](P& p) { p.angle_step_deg = 0.0f; });
  expectRejected<P>("angle_step_deg", [](P& p) { p.angle_step_deg = 200.0f; });
  expectRejected<P>("dense_samples_per_step2", [](P& p) { p.dense_samples_per_step2 = 0.0f; });
  expectRejected<P>("normal_radius_ratio", [](P& p) { p.normal_radius_ratio = -1.0f; });
  expectRejected<P>("normal_radius_ratio", [](P& p) { p.normal_radius_ratio = kInf; });
  expectRejected<P>("normal_cluster_angle_deg", [](P& p) { p.normal_cluster_angle_deg = -5.0f; });
  expectRejected<P>("normal_cluster_angle_deg", [](P& p) { p.normal_cluster_angle_deg = kNaN; });
}

TEST(Params, SceneParamsNameTheField) {
  using P = SceneParams;
  expectRejected<P>("min_normal_neighbours", [](P& p) { p.min_normal_neighbours = 2; });
  expectRejected<P>("max_window_half_size", [](P& p) { p.max_window_half_size = 0; });
  expectRejected<P>("max_window_half_size", [](P& p) { p.max_window_half_size = 1000; });
  expectRejected<P>("crop", [](P& p) { p.crop = CropBox{}; });  // zero half extents
  expectRejected<P>("crop", [](P& p) {
    CropBox box;
    box.half_extents = {0.1f, kNaN, 0.1f};
    p.crop = box;
  });
  expectRejected<P>("crop", [](P& p) {
    CropBox box;
    box.half_extents = {0.1f, 0.1f, 0.1f};
    box.T_camera_box.translation().x() = kInf;
    p.crop = box;
  });
}

TEST(Params, VotingParamsNameTheField) {
  using P = VotingParams;
  expectRejected<P>("reference_fraction", [](P& p) { p.reference_fraction = 0.0f; });
  expectRejected<P>("reference_fraction", [](P& p) { p.reference_fraction = 1.5f; });
  expectRejected<P>("reference_fraction", [](P& p) { p.reference_fraction = kNaN; });
  expectRejected<P>("referred_fraction", [](P& p) { p.referred_fraction = -0.2f; });
  expectRejected<P>("referred_fraction", [](P& p) { p.referred_fraction = kNaN; });
  expectRejected<P>("poses_per_reference", [](P& p) { p.poses_per_reference = 0; });
  expectRejected<P>("poses_per_reference", [](P& p) { p.poses_per_reference = 100000; });
  expectRejected<P>("min_relative_votes", [](P& p) { p.min_relative_votes = -0.1f; });
  expectRejected<P>("min_relative_votes", [](P& p) { p.min_relative_votes = kNaN; });
  // vote() itself refuses them too.
  PreparedScene scene;
  VotingParams bad;
  bad.reference_fraction = 0.0f;
  EXPECT_NE(errorMessage([&] { vote(smallModel(), scene, bad); }).find("reference_fraction"), std::string::npos);
}

TEST(Params, BoundaryParamsNameTheField) {
  using P = BoundaryParams;
  expectRejected<P>("depth_jump_ratio", [](P& p) { p.depth_jump_ratio = 0.0f; });
  expectRejected<P>("depth_jump_ratio", [](P& p) { p.depth_jump_ratio = kNaN; });
  expectRejected<P>("crease_angle_deg", [](P& p) { p.crease_angle_deg = 180.0f; });
  expectRejected<P>("crease_angle_deg", [](P& p) { p.crease_angle_deg = kNaN; });
  expectRejected<P>("min_linearity", [](P& p) { p.min_linearity = 0.5f; });
  expectRejected<P>("min_linearity", [](P& p) { p.min_linearity = kInf; });
}

TEST(Params, VerificationSelectionIcpClusteringNameTheField) {
  expectRejected<VerificationParams>("voxel_size_ratio", [](auto& p) { p.voxel_size_ratio = 0.0f; });
  expectRejected<VerificationParams>("voxel_size_ratio", [](auto& p) { p.voxel_size_ratio = kNaN; });
  expectRejected<VerificationParams>("max_normal_angle_deg", [](auto& p) { p.max_normal_angle_deg = 0.0f; });
  expectRejected<VerificationParams>("max_normal_angle_deg", [](auto& p) { p.max_normal_angle_deg = 181.0f; });

  expectRejected<SelectionParams>("max_objects", [](auto& p) { p.max_objects = 0; });
  expectRejected<SelectionParams>("min_score_fraction", [](auto& p) { p.min_score_fraction = 1.5f; });
  expectRejected<SelectionParams>("min_score_fraction", [](auto& p) { p.min_score_fraction = kNaN; });
  expectRejected<SelectionParams>("min_centre_distance_ratio", [](auto& p) { p.min_centre_distance_ratio = -1.0f; });
  expectRejected<SelectionParams>("sure_twin_margin", [](auto& p) { p.sure_twin_margin = kNaN; });
  expectRejected<SelectionParams>("sure_coverage", [](auto& p) { p.sure_coverage = 1.5f; });

  expectRejected<IcpParams>("max_iterations", [](auto& p) { p.max_iterations = -1; });
  expectRejected<IcpParams>("initial_max_distance_ratio", [](auto& p) { p.initial_max_distance_ratio = 0.0f; });
  expectRejected<IcpParams>("final_max_distance_ratio", [](auto& p) { p.final_max_distance_ratio = kNaN; });
  expectRejected<IcpParams>("huber_ratio", [](auto& p) { p.huber_ratio = -1.0f; });
  expectRejected<IcpParams>("convergence_translation_ratio", [](auto& p) { p.convergence_translation_ratio = kInf; });
  expectRejected<IcpParams>("convergence_rotation_deg", [](auto& p) { p.convergence_rotation_deg = 0.0f; });
  expectRejected<IcpParams>("fit_distance_ratio", [](auto& p) { p.fit_distance_ratio = 0.0f; });

  expectRejected<ClusteringParams>("max_translation_ratio", [](auto& p) { p.max_translation_ratio = 0.0f; });
  expectRejected<ClusteringParams>("max_rotation_deg", [](auto& p) { p.max_rotation_deg = kNaN; });
}

TEST(Params, DetectorRejectsBadParams) {
  expectRejected<DetectorParams>("threads", [](auto& p) { p.threads = -1; });
  EXPECT_NO_THROW(DetectorParams::drost(0.2f).validate());
  EXPECT_NO_THROW(DetectorParams::drost(1.0f).validate());
  EXPECT_NE(errorMessage([] { DetectorParams::drost(0.0f).validate(); }).find("reference_fraction"), std::string::npos);

  const auto detectorError = [](const std::function<void(DetectorParams&)>& change) {
    DetectorParams p;
    change(p);
    return errorMessage([&] { Detector(smallModel(), p); });
  };
  EXPECT_NE(detectorError([](auto& p) { p.voting.reference_fraction = 0.0f; }).find("reference_fraction"),
            std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.scene.min_normal_neighbours = 0; }).find("min_normal_neighbours"),
            std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.verification.voxel_size_ratio = 100.0f; }).find("voxel_size_ratio"),
            std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.selection.max_objects = -3; }).find("max_objects"), std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.icp.huber_ratio = 0.0f; }).find("huber_ratio"), std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.clustering.max_rotation_deg = 0.0f; }).find("max_rotation_deg"),
            std::string::npos);
  EXPECT_NE(detectorError([](auto& p) { p.threads = -1; }).find("threads"), std::string::npos);
  EXPECT_NE(errorMessage([] { Detector(PreparedModel{}, DetectorParams{}); }), "") << "a model without points";

  EXPECT_EQ(methodFromName("li_hashimoto"), Method::LiHashimoto);
  EXPECT_EQ(methodFromName("drost"), Method::Drost);
  EXPECT_EQ(methodFromName(methodName(Method::Drost)), Method::Drost);
  EXPECT_EQ(methodFromName(methodName(Method::LiHashimoto)), Method::LiHashimoto);
  EXPECT_NE(errorMessage([] { methodFromName("ppf"); }).find("ppf"), std::string::npos);
}

TEST(Params, PrepareModelRejectsEmptyAndDegenerateGeometry) {
  EXPECT_NE(errorMessage([] { prepareModel(io::ModelGeometry{}, ModelParams{}); }), "");
  // Every triangle degenerate: collinear corners, and a repeated corner.
  io::ModelGeometry flat;
  flat.mesh.vertices = {{0, 0, 0}, {0.05f, 0, 0}, {0.1f, 0, 0}, {0.1f, 0.1f, 0}};
  flat.mesh.triangles = {{0, 1, 2}, {1, 3, 3}, {2, 2, 2}};
  EXPECT_NE(errorMessage([&] { prepareModel(flat, ModelParams{}); }), "");
  // Bad indices and NaN vertices.
  io::ModelGeometry broken;
  broken.mesh.vertices = {{0, 0, 0}, {0.05f, 0, 0}, {0, 0.05f, 0}};
  broken.mesh.triangles = {{0, 1, 7}};
  EXPECT_NE(errorMessage([&] { prepareModel(broken, ModelParams{}); }), "");
  broken.mesh.triangles = {{0, 1, 2}};
  broken.mesh.vertices[1].x() = kNaN;
  EXPECT_NE(errorMessage([&] { prepareModel(broken, ModelParams{}); }), "");
  // A cloud of too few points, and nonsense params with a good mesh.
  io::ModelGeometry few;
  few.cloud.points = {{0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}};
  EXPECT_NE(errorMessage([&] { prepareModel(few, ModelParams{}); }), "");
  ModelParams bad;
  bad.sampling_ratio = 0.0f;
  EXPECT_NE(errorMessage([&] {
              prepareModel(io::ModelGeometry{simulation::makePart("clamp").mesh, {}}, bad);
            }).find("sampling_ratio"),
            std::string::npos);
}

TEST(Params, EmptyScenesAreValuesAndMalformedCloudsThrow) {
  const PreparedModel& model = smallModel();
  const io::PointCloud empty;
  const PreparedScene scene = prepareScene(empty, model, SceneParams{});
  EXPECT_EQ(scene.size(), 0u);
  EXPECT_EQ(scene.valid_input_points, 0u);

  const Detector detector(model, DetectorParams{});
  DetectionResult result;
  ASSERT_NO_THROW(result = detector.detect(empty));
  EXPECT_TRUE(result.detections.empty());
  EXPECT_EQ(result.scene_points, 0u);
  EXPECT_EQ(result.candidates, 0u);

  // An organized cloud of nothing but invalid pixels: also an empty result.
  io::PointCloud invalid;
  invalid.width = 4;
  invalid.height = 3;
  invalid.points.assign(12, Eigen::Vector3f::Constant(kNaN));
  EXPECT_EQ(prepareScene(invalid, model, SceneParams{}).size(), 0u);
  ASSERT_NO_THROW(result = detector.detect(invalid));
  EXPECT_TRUE(result.detections.empty());

  // A cloud entirely outside the crop box: empty as well.
  io::PointCloud outside;
  for (int i = 0; i < 100; ++i) outside.points.emplace_back(0.001f * i, 0.0f, 5.0f);
  SceneParams cropped;
  cropped.crop = CropBox{};
  cropped.crop->half_extents = {0.1f, 0.1f, 0.1f};
  EXPECT_EQ(prepareScene(outside, model, cropped).size(), 0u);
  EXPECT_EQ(prepareScene(outside, model, cropped).valid_input_points, 0u);

  // An unorganized cloud with a NaN point, or normals of the wrong count: malformed input.
  io::PointCloud nan_cloud = outside;
  nan_cloud.points[17].y() = kNaN;
  EXPECT_NE(errorMessage([&] { prepareScene(nan_cloud, model, SceneParams{}); }), "");
  EXPECT_NE(errorMessage([&] { detector.detect(nan_cloud); }), "");
  io::PointCloud bad_normals = outside;
  bad_normals.normals.assign(3, Eigen::Vector3f::UnitZ());
  EXPECT_NE(errorMessage([&] { prepareScene(bad_normals, model, SceneParams{}); }), "");
}

}  // namespace
}  // namespace binpick::estimation
