// A model given as a point cloud with normals (a scan, or a CAD export without faces) instead of
// a mesh: the same pipeline must find the parts.
#include <gtest/gtest.h>

#include <random>

#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

// Uniform samples on every triangle in proportion to its area, with the face normal: what a
// cloud exported from CAD holds.
io::PointCloud sampledCloud(const io::TriangleMesh& mesh, float points_per_mm2, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  io::PointCloud cloud;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const Eigen::Vector3f cross = (b - a).cross(c - a);
    const float area = 0.5f * cross.norm();
    const auto count = static_cast<std::size_t>(area * 1e6f * points_per_mm2) + 1;  // area in m^2
    for (std::size_t k = 0; k < count; ++k) {
      float u = uniform(rng), v = uniform(rng);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      cloud.points.push_back(a + u * (b - a) + v * (c - a));
      cloud.normals.push_back(cross.normalized());
    }
  }
  return cloud;
}

TEST(ModelFromCloud, CloudWithNormalsFindsTheHalfVisibleParts) {
  const simulation::Part part = simulation::makePart("l_bracket");
  const io::PointCloud model_cloud = sampledCloud(part.mesh, 4.0f, 3);  // about 4 points per mm^2
  ASSERT_GT(model_cloud.size(), 20000u);
  const PreparedModel model = prepareModel(io::ModelGeometry{{}, model_cloud}, ModelParams{});

  simulation::PileParams pile;
  pile.objects = 10;
  pile.seed = 21;
  const simulation::PileScene scene = simulation::generatePile(part.mesh, pile);
  DetectorParams params;
  params.selection.max_objects = pile.objects;
  params.scene.crop = evaluation::binInterior(scene, pile);
  const DetectionResult result = Detector(model, params).detect(scene.cloud);
  const DetectionResult from_mesh = Detector(estimation::testing::cachedModel("l_bracket"), params).detect(scene.cloud);

  const evaluation::Score score =
      evaluation::scoreDetections(result.detections, scene.objects, part.symmetry, {model.diameter / 10.0, 10.0});
  const evaluation::Score mesh_score =
      evaluation::scoreDetections(from_mesh.detections, scene.objects, part.symmetry, {model.diameter / 10.0, 10.0});
  ASSERT_GT(score.findable, 3);
  // A densely sampled cloud with normals is as good a model as the mesh it was sampled from.
  EXPECT_GE(score.found, mesh_score.found - 1);
  EXPECT_GE(score.found, score.findable / 2);
  for (std::size_t d = 0; d < std::min<std::size_t>(3, result.detections.size()); ++d) {
    EXPECT_GE(score.matched_object[d], 0) << "detection " << d;
  }
}

}  // namespace
}  // namespace binpick::estimation
