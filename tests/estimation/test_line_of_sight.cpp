// The map of what the camera saw along each line of sight, and the scene-consistent verification
// built on it: a pose pays for model points lying in front of the measured surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/pile.hpp"
#include "estimation_test_support.hpp"
#include "icp.hpp"
#include "line_of_sight.hpp"
#include "scene.hpp"
#include "verification.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;

// A plane at `depth` seen over directions x/z, y/z in [-half, half], one point per `pitch`.
std::vector<Eigen::Vector3f> planeAt(float depth, float half, float pitch) {
  std::vector<Eigen::Vector3f> points;
  for (float u = -half; u <= half; u += pitch) {
    for (float v = -half; v <= half; v += pitch) points.emplace_back(u * depth, v * depth, depth);
  }
  return points;
}

TEST(LineOfSightMap, HoldsTheNearestMeasuredDepthAlongEachDirection) {
  std::vector<Eigen::Vector3f> points = planeAt(1.0f, 0.2f, 0.001f);
  for (const Eigen::Vector3f& p : planeAt(0.8f, 0.05f, 0.001f)) points.push_back(p);  // a box in front
  const float nan = std::nanf("");
  points.emplace_back(nan, 0.0f, 1.0f);
  points.emplace_back(0.0f, 0.0f, -1.0f);  // behind the camera
  const LineOfSightMap map(points, 0.004f, 1.0f);
  ASSERT_FALSE(map.empty());

  EXPECT_NEAR(map.measuredDepth({0.0f, 0.0f, 0.5f}), 0.8f, 1e-5f);   // in front of the box: its depth
  EXPECT_NEAR(map.measuredDepth({0.2f, 0.2f, 2.0f}), 1.0f, 1e-5f);   // the far plane, any range
  EXPECT_NEAR(map.measuredDepth({-0.15f, 0.12f, 1.0f}), 1.0f, 1e-5f);
  EXPECT_EQ(map.measuredDepth({0.5f, 0.0f, 1.0f}), LineOfSightMap::kUnseen);  // outside what was seen
  EXPECT_EQ(map.measuredDepth({0.0f, 0.0f, -1.0f}), LineOfSightMap::kUnseen);
  EXPECT_EQ(map.measuredDepth({nan, 0.0f, 1.0f}), LineOfSightMap::kUnseen);
  EXPECT_EQ(map.measuredDepth({std::numeric_limits<float>::infinity(), 0.0f, 1.0f}), LineOfSightMap::kUnseen);
}

TEST(LineOfSightMap, APointIsSeenThroughOnlyWellInFrontOfTheMeasuredSurface) {
  const LineOfSightMap map(planeAt(1.0f, 0.2f, 0.001f), 0.004f, 1.0f);
  EXPECT_TRUE(map.seenThrough({0.0f, 0.0f, 0.9f}, 0.05f));
  EXPECT_FALSE(map.seenThrough({0.0f, 0.0f, 0.9f}, 0.2f));    // within the tolerance
  EXPECT_FALSE(map.seenThrough({0.0f, 0.0f, 1.1f}, 0.05f));   // behind: hidden, not seen through
  EXPECT_FALSE(map.seenThrough({0.6f, 0.0f, 0.9f}, 0.05f));   // nothing measured there: unknown

  // With its surface normal: only where the camera would have measured the point.
  const Eigen::Vector3f p(0.0f, 0.0f, 0.9f);
  EXPECT_TRUE(map.seenThrough(p, Eigen::Vector3f(0.0f, 0.0f, -1.0f), 0.05f));               // facing
  EXPECT_TRUE(map.seenThrough(p, Eigen::Vector3f(0.0f, 0.7f, -0.7f).normalized(), 0.05f));  // 45 degrees
  EXPECT_FALSE(map.seenThrough(p, Eigen::Vector3f(0.0f, 1.0f, -0.1f).normalized(), 0.05f)); // grazing
  EXPECT_FALSE(map.seenThrough(p, Eigen::Vector3f(0.0f, 0.0f, 1.0f), 0.05f));               // facing away
}

TEST(LineOfSightMap, HolesInTheCloudAreUnknownNotFree) {
  std::vector<Eigen::Vector3f> points = planeAt(1.0f, 0.2f, 0.001f);
  const auto in_shadow = [](const Eigen::Vector3f& p) { return std::abs(p.x()) < 0.03f && std::abs(p.y()) < 0.03f; };
  points.erase(std::remove_if(points.begin(), points.end(), in_shadow), points.end());
  const LineOfSightMap map(points, 0.004f, 1.0f);
  EXPECT_EQ(map.measuredDepth({0.0f, 0.0f, 1.0f}), LineOfSightMap::kUnseen);  // a shadow
  EXPECT_FALSE(map.seenThrough({0.0f, 0.0f, 0.5f}, 0.01f));
}

TEST(LineOfSightMap, StrayPointsAtWideAnglesKeepTheMapSmall) {
  std::vector<Eigen::Vector3f> points = planeAt(1.0f, 0.2f, 0.001f);
  points.emplace_back(1000.0f, -1000.0f, 1e-3f);
  points.emplace_back(-1000.0f, 1000.0f, 1e-3f);
  const LineOfSightMap map(points, 0.0001f, 1.0f);
  EXPECT_LE(static_cast<double>(map.width()) * map.height(), 4.1e6);
  EXPECT_NEAR(map.measuredDepth({0.0f, 0.0f, 0.5f}), 1.0f, 1e-5f);
}

TEST(LineOfSightMap, BadCellSizesAreRefused) {
  const std::vector<Eigen::Vector3f> points = planeAt(1.0f, 0.1f, 0.01f);
  for (float cell : {0.0f, -1.0f, std::nanf("")}) {
    EXPECT_THROW(LineOfSightMap(points, cell, 1.0f), core::Error) << cell;
  }
  EXPECT_THROW(LineOfSightMap(points, 0.004f, 0.0f), core::Error);
  EXPECT_TRUE(LineOfSightMap({}, 0.004f, 1.0f).empty());
}

// On a physical pile seen by the ideal sensor: every part's true pose is consistent with what the
// camera saw, and the same pose moved towards the camera (floating over the pile) or turned over
// is not.
TEST(SceneConsistentVerification, TruePosesPassAndPosesFloatingOrTurnedOverAreSeenThrough) {
  const std::string part = "bulge";
  const PreparedModel& model = cachedModel(part);
  simulation::PileParams params;
  params.objects = 12;
  params.seed = 5;
  params.bin_length = 0.24;
  params.bin_width = 0.18;
  const simulation::PileScene pile = simulation::generatePile(simulation::makePart(part).mesh, params);
  SceneParams scene_params;
  scene_params.crop = evaluation::binInterior(pile, params);
  const PreparedScene scene = prepareScene(pile.cloud, model, scene_params);
  ASSERT_FALSE(scene.line_of_sight.empty());
  const float tolerance = VerificationParams{}.refined_tolerance_ratio * model.step;

  int checked = 0;
  for (const simulation::ObjectTruth& object : pile.objects) {
    if (object.visible_fraction < 0.5) continue;
    ++checked;
    const Eigen::Isometry3f truth = object.T_camera_object.cast<float>();
    const std::vector<uint32_t> visible = visibleModelPoints(model, truth);
    ASSERT_FALSE(visible.empty());
    const auto share = [&](const Eigen::Isometry3f& pose) {
      const std::vector<uint32_t> seen = visibleModelPoints(model, pose);
      return static_cast<float>(seenThroughCount(model, pose, scene.line_of_sight, tolerance, &seen)) /
             static_cast<float>(seen.size());
    };
    EXPECT_LT(share(truth), 0.03f) << "object at " << truth.translation().transpose();

    Eigen::Isometry3f floating = truth;
    floating.translation() -= 3.0f * model.step * truth.translation().normalized();
    EXPECT_GT(share(floating), 0.5f);

    // Turned over about the plate's long axis through its centre: the outline is mirrored, and the
    // bulge (about 6% of the plate) now hangs where the camera saw what lies behind the part.
    Eigen::Isometry3f turned = truth;
    turned.translate(model.centre).rotate(Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitX()));
    turned.translate(-model.centre);
    EXPECT_GT(share(turned), share(truth) + 0.02f);
  }
  EXPECT_GE(checked, 3);
}

}  // namespace
}  // namespace binpick::estimation
