// Boundary-aware pairs (Choi et al. 2012): the surface-to-boundary feature, the scene's outline
// from an organized cloud's depth discontinuities, the model's convex creases, and what they fix
// on a pile: long brackets standing on their L profile, whose one visible face is a 6 mm strip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/pile.hpp"
#include "boundary.hpp"
#include "estimation_test_support.hpp"
#include "voting.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;
using testing::deg;

TEST(BoundaryFeature, IgnoresTheSignOfTheLineDirection) {
  const Eigen::Vector3f p(0.0f, 0.0f, 0.0f), n(0.0f, 0.0f, 1.0f), b(0.03f, 0.01f, -0.005f);
  const Eigen::Vector3f l = Eigen::Vector3f(1.0f, 2.0f, 0.5f).normalized();
  const PointPairFeature f = computeBoundaryFeature(p, n, b, l);
  const PointPairFeature g = computeBoundaryFeature(p, n, b, -l);
  EXPECT_FLOAT_EQ(f.distance, g.distance);
  EXPECT_FLOAT_EQ(f.angle_ni_d, g.angle_ni_d);
  EXPECT_NEAR(f.angle_nj_d, g.angle_nj_d, 1e-6f);
  EXPECT_NEAR(f.angle_ni_nj, g.angle_ni_nj, 1e-6f);
  EXPECT_LE(f.angle_nj_d, static_cast<float>(M_PI / 2) + 1e-6f);
  EXPECT_LE(f.angle_ni_nj, static_cast<float>(M_PI / 2) + 1e-6f);
}

// An organized view, from 0.5 m, of a 60 mm square plate 20 mm above a floor: the plate's outline
// is the near side of a depth jump; the floor around it is the far side and no boundary.
io::PointCloud plateOverFloor() {
  io::PointCloud cloud;
  cloud.width = 400, cloud.height = 400;
  const float focal = 1000.0f, floor_z = 0.5f, plate_z = 0.48f, half_plate = 0.03f;
  for (int v = 0; v < cloud.height; ++v) {
    for (int u = 0; u < cloud.width; ++u) {
      const float x = (static_cast<float>(u) - 200.0f) / focal, y = (static_cast<float>(v) - 200.0f) / focal;
      const bool on_plate = std::abs(x * plate_z) <= half_plate && std::abs(y * plate_z) <= half_plate;
      const float z = on_plate ? plate_z : floor_z;
      cloud.points.emplace_back(x * z, y * z, z);
    }
  }
  return cloud;
}

TEST(SceneBoundary, FindsTheNearSideOfADepthJumpWithItsDirection) {
  const PreparedModel& model = cachedModel("l_bracket_long");  // step 4.7 mm < the 20 mm jump
  BoundaryParams params;
  params.enabled = true;
  const BoundaryPoints boundary = sceneBoundaryPoints(plateOverFloor(), std::nullopt, model, params);
  // The outline is 240 mm long: about one point per step, corners without a direction left out.
  EXPECT_GE(boundary.size(), static_cast<std::size_t>(0.6f * 0.24f / model.step));
  for (std::size_t k = 0; k < boundary.size(); ++k) {
    const Eigen::Vector3f& p = boundary.points[k];
    EXPECT_NEAR(p.z(), 0.48f, 1e-4f) << "boundary point " << k << " is not on the plate";
    EXPECT_NEAR(std::max(std::abs(p.x()), std::abs(p.y())), 0.03f, 0.002f) << "point " << k << " is not at the edge";
    // Along the edge it lies on (x for the edges at |y| = 30 mm, y for the others), except within
    // a step of a corner, where the line bends.
    const bool on_x_edge = std::abs(p.y()) > std::abs(p.x());
    const float along_edge = on_x_edge ? std::abs(p.x()) : std::abs(p.y());
    if (along_edge > 0.03f - model.step) {
      continue;
    }
    const Eigen::Vector3f along = on_x_edge ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
    EXPECT_LT(deg(std::acos(std::min(1.0f, std::abs(boundary.directions[k].dot(along))))), 10.0) << "point " << k;
  }
  io::PointCloud unorganized = plateOverFloor();
  unorganized.width = unorganized.height = 0;
  EXPECT_EQ(sceneBoundaryPoints(unorganized, std::nullopt, model, params).size(), 0u);
}

TEST(ModelBoundary, KeepsTheConvexCreasesOfAPrismaticPart) {
  const PreparedModel& model = cachedModel("l_bracket_long");
  const BoundaryModel boundary = prepareBoundaryModel(model, BoundaryParams{});
  RecordProperty("creases", static_cast<int>(boundary.creases.size()));
  ASSERT_GT(boundary.creases.size(), 20u);
  EXPECT_GT(boundary.table.pairCount(), 0u);
  // An extruded L has its creases along its three axes only.
  for (std::size_t k = 0; k < boundary.creases.size(); ++k) {
    const Eigen::Vector3f a = boundary.creases.directions[k].cwiseAbs();
    EXPECT_GT(a.maxCoeff(), std::cos(testing::rad(10.0f))) << "crease point " << k << " is not along an axis";
  }
}

// The bench's first l_bracket_long pile (20 parts dropped in the 400 x 300 mm bin, seed 1): the
// parts standing on their L profile (extrusion axis within 15 degrees of the line of sight) show
// the camera a 6 mm L strip, one or two steps wide. Its surface pairs all share a normal and vote
// like any flat face of the bracket; the outline's pairs tell the L.
TEST(BoundaryPairs, FindLongBracketsStandingOnTheirProfile) {
  const std::string part_name = "l_bracket_long";
  const simulation::Part part = simulation::makePart(part_name);
  const PreparedModel& model = cachedModel(part_name);
  simulation::PileParams pile;
  pile.objects = 20;
  pile.seed = 1;
  const simulation::PileScene scene = simulation::generatePile(part.mesh, pile);
  std::vector<int> standing;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const auto& T = scene.objects[i].T_camera_object;
    const Eigen::Vector3d towards_camera = -T.translation().normalized();
    if (scene.objects[i].visible_fraction >= 0.5 &&
        std::abs(T.linear().col(2).dot(towards_camera)) > std::cos(15.0 * M_PI / 180.0)) {
      standing.push_back(static_cast<int>(i));
    }
  }
  ASSERT_GE(standing.size(), 3u);

  const auto detect = [&](bool boundary_pairs, int& wrong_in_first_10) {
    DetectorParams params;
    params.selection.max_objects = pile.objects;
    params.scene.crop = evaluation::binInterior(scene, pile);
    params.boundary.enabled = boundary_pairs;
    const DetectionResult result = Detector(model, params).detect(scene.cloud);
    const evaluation::Score s =
        evaluation::scoreDetections(result.detections, scene.objects, part.symmetry, {model.diameter / 10.0, 10.0});
    wrong_in_first_10 = s.wrong_in_first_10;
    int found = 0;
    for (int i : standing) found += std::count(s.matched_object.begin(), s.matched_object.end(), i) > 0;
    return found;
  };
  int wrong_without = 0, wrong_with = 0;
  const int found_without = detect(false, wrong_without);
  const int found_with = detect(true, wrong_with);
  RecordProperty("standing", static_cast<int>(standing.size()));
  RecordProperty("found_without", found_without);
  RecordProperty("found_with", found_with);
  SCOPED_TRACE(std::to_string(standing.size()) + " standing; found without " + std::to_string(found_without) +
               ", with " + std::to_string(found_with));
  EXPECT_GE(found_with, found_without + 2);
  EXPECT_GE(found_with, static_cast<int>(standing.size()) - 1);
  EXPECT_LE(wrong_with, wrong_without);
  EXPECT_EQ(wrong_with, 0);
}

}  // namespace
}  // namespace binpick::estimation
