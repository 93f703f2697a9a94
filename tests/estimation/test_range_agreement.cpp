// Judging a refined pose against the measured range, and ICP holding a part where it lies: what
// lets the detector tell a part lying on one face from the same part turned over.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/pile.hpp"
#include "estimation_test_support.hpp"
#include "icp.hpp"
#include "range_agreement.hpp"
#include "scene.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;

struct Pile {
  simulation::PileScene truth;
  CropBox crop;
  PreparedScene scene;
};

Pile pileOf(const std::string& part, uint64_t seed) {
  simulation::PileParams params;
  params.objects = 10;
  params.seed = seed;
  params.bin_length = 0.24;
  params.bin_width = 0.18;
  Pile pile{simulation::generatePile(simulation::makePart(part).mesh, params), {}, {}};
  pile.crop = evaluation::binInterior(pile.truth, params);
  SceneParams scene_params;
  scene_params.crop = pile.crop;
  pile.scene = prepareScene(pile.truth.cloud, cachedModel(part), scene_params);
  return pile;
}

// The angle between the part's z axis (the switch's extrusion) and the line of sight, degrees.
double zAxisFromView(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d towards_camera = -pose.translation().normalized();
  return testing::deg(std::acos(std::min(1.0, std::abs(pose.linear().col(2).dot(towards_camera)))));
}

TEST(RangeAgreement, FloorPlaneExplainsAPlateOnItAndSeesThroughOneAboveIt) {
  const PreparedModel& model = cachedModel("bulge");
  std::vector<Eigen::Vector3f> floor;
  for (float x = -0.1f; x <= 0.1f; x += 0.0005f) {
    for (float y = -0.1f; y <= 0.1f; y += 0.0005f) floor.emplace_back(x, y, 1.0f);
  }
  const LineOfSightMap map(floor, 0.5f * model.step, 1.0f);
  // The plate (15 mm thick, extruded along z) with its top face on the measured plane.
  Eigen::Isometry3f lying = Eigen::Isometry3f::Identity();
  lying.translation() = Eigen::Vector3f(0.0f, 0.0f, 1.0f + 0.0075f);
  const float tolerance = model.step;
  const RangeAgreement on = rangeAgreement(model, lying, map, tolerance);
  EXPECT_GT(on.visible, 100);
  EXPECT_GE(on.explained, on.visible * 9 / 10);
  EXPECT_EQ(on.seen_through, 0);

  Eigen::Isometry3f floating = lying;
  floating.translation().z() -= 0.05f;  // 5 cm in front of what the camera measured
  const RangeAgreement above = rangeAgreement(model, floating, map, tolerance);
  EXPECT_GE(above.seen_through, above.visible * 9 / 10);
  EXPECT_LT(above.consistency(), 0);

  Eigen::Isometry3f sunk = lying;
  sunk.translation().z() += 0.05f;  // behind the plane: hidden, no evidence either way
  const RangeAgreement below = rangeAgreement(model, sunk, map, tolerance);
  EXPECT_EQ(below.hidden, below.visible);

  EXPECT_EQ(rangeAgreement(model, lying, LineOfSightMap{}, tolerance).unseen, on.visible);
}

// A switch housing lying on its profile shows a 60 x 42 mm face whose outline differs from its
// mirror image only by the slope of the rocker: a few millimetres along 30 mm of edge. The
// detector compares each pick with its turned twins against the range, and hands out few such
// parts turned over.
TEST(DetectorTurnedTwins, FewSwitchesLyingOnTheirProfileAreReturnedTurnedOver) {
  const simulation::Part part = simulation::makePart("switch");
  const PreparedModel& model = cachedModel("switch");
  int checked = 0, turned_over = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const Pile pile = pileOf("switch", seed);
    DetectorParams params;
    params.scene.crop = pile.crop;
    const DetectionResult result = Detector(model, params).detect(pile.truth.cloud);
    for (const simulation::ObjectTruth& object : pile.truth.objects) {
      if (object.visible_fraction < 0.95 || zAxisFromView(object.T_camera_object) > 15.0) continue;
      const Detection* nearest = nullptr;
      for (const Detection& d : result.detections) {
        if (!nearest || testing::translationError(d.T_camera_model, object.T_camera_object.cast<float>()) <
                            testing::translationError(nearest->T_camera_model, object.T_camera_object.cast<float>())) {
          nearest = &d;
        }
      }
      if (!nearest || testing::translationError(nearest->T_camera_model, object.T_camera_object.cast<float>()) >
                          0.1 * model.diameter) {
        continue;  // not found at all: a matter of recall, not of turning over
      }
      ++checked;
      const simulation::PoseError error =
          simulation::poseError(nearest->T_camera_model.cast<double>(), object.T_camera_object, part.symmetry);
      turned_over += error.rotation_deg > 10.0 ? 1 : 0;
    }
  }
  // With verification.compare_turned off, 5 of these 10 parts come out turned over. With it, 3
  // (2 without the outline's votes, boundary.enabled false: other parts, other seeds): all picked
  // 9th to 11th, where the turned pose and the truth agree with the range within a few percent.
  EXPECT_GE(checked, 8);
  EXPECT_LE(turned_over, 3);
}

// Each of the first `piles` piles of a part, detected with the default settings, and its score.
struct ScoredPile {
  DetectionResult result;
  evaluation::Score score;
};

std::vector<ScoredPile> detectedPiles(const std::string& part_name, uint64_t piles) {
  const simulation::Part part = simulation::makePart(part_name);
  const PreparedModel& model = cachedModel(part_name);
  std::vector<ScoredPile> scored;
  for (uint64_t seed = 1; seed <= piles; ++seed) {
    const Pile pile = pileOf(part_name, seed);
    DetectorParams params;
    params.scene.crop = pile.crop;
    ScoredPile s{Detector(model, params).detect(pile.truth.cloud), {}};
    s.score = evaluation::scoreDetections(s.result.detections, pile.truth.objects, part.symmetry,
                                          {0.1 * model.diameter, 10.0});
    scored.push_back(std::move(s));
  }
  return scored;
}

// What the range cannot tell apart comes last: a detection whose turned twin explains the range
// about as well, or whose fit covers little of what the camera should see, is not `sure` and is
// returned after the sure ones. On these switch piles the wrong detections are such.
TEST(DetectorTurnedTwins, DetectionsTheRangeIsNotSureOfComeLast) {
  const SelectionParams defaults;
  int wrong_sure = 0, wrong_unsure = 0, right_sure = 0;
  for (const ScoredPile& pile : detectedPiles("switch", 6)) {
    const std::vector<Detection>& detections = pile.result.detections;
    for (std::size_t k = 0; k < detections.size(); ++k) {
      const Detection& d = detections[k];
      if (k > 0) {
        EXPECT_FALSE(d.sure && !detections[k - 1].sure) << "a sure detection after an unsure one";
      }
      EXPECT_EQ(d.sure, d.twin_margin >= defaults.sure_twin_margin && d.coverage >= defaults.sure_coverage);
      // Poses leave the detector orthonormal: what reads them back (JSON, the robot) checks.
      EXPECT_LT(
          (d.T_camera_model.linear() * d.T_camera_model.linear().transpose() - Eigen::Matrix3f::Identity()).norm(),
          1e-5f);
      const bool right = pile.score.matched_object[k] >= 0;
      wrong_sure += !right && d.sure ? 1 : 0;
      wrong_unsure += !right && !d.sure ? 1 : 0;
      right_sure += right && d.sure ? 1 : 0;
    }
  }
  const std::string counts = std::to_string(right_sure) + " right and " + std::to_string(wrong_sure) +
                             " wrong detections were sure, " + std::to_string(wrong_unsure) + " wrong ones not";
  // Measured: 34 right and 0 wrong detections sure, 17 wrong ones not (of 6 piles of 10).
  EXPECT_GE(right_sure, 30) << counts;
  EXPECT_LE(wrong_sure, 2) << counts;
  EXPECT_GE(wrong_unsure, 8) << counts;
}

// A long bracket turned end for end lies on its own long leg once slid along it by tens of
// millimetres; only its short leg, at the other end, tells the two apart. Such a pose must not
// come out sure: its slid twin explains the range about as well or better.
TEST(DetectorTurnedTwins, ALongBracketTurnedEndForEndIsNotSure) {
  int wrong_sure = 0, right_sure = 0, right = 0;
  for (const ScoredPile& pile : detectedPiles("l_bracket_long", 14)) {
    for (std::size_t k = 0; k < pile.result.detections.size(); ++k) {
      const bool is_right = pile.score.matched_object[k] >= 0;
      right += is_right ? 1 : 0;
      wrong_sure += !is_right && pile.result.detections[k].sure ? 1 : 0;
      right_sure += is_right && pile.result.detections[k].sure ? 1 : 0;
    }
  }
  const std::string counts = std::to_string(right_sure) + " of " + std::to_string(right) + " right detections and " +
                             std::to_string(wrong_sure) + " wrong ones were sure";
  // Measured on these 14 piles: 73 of 106 right and 2 wrong detections sure; judged against the
  // turned twins alone (no slid ones), 82 right and 9 wrong.
  EXPECT_LE(wrong_sure, 4) << counts;
  EXPECT_GE(right_sure, 60) << counts;
}

// Point-to-plane ICP lets a part lying on a face slide along it; the point-to-point share holds it
// where its outline is. From the true pose, ICP must stay there: 0.15 mm median and 1.7 mm at most
// over 11 parts (point-to-plane alone, point_weight 0: 1.4 and 6.4 mm).
TEST(PoseRefiner, KeepsALongBracketLyingFlatWhereItLies) {
  const PreparedModel& model = cachedModel("l_bracket_long");
  std::vector<double> drift_mm;
  for (uint64_t seed : {1u, 2u}) {
    const Pile pile = pileOf("l_bracket_long", seed);
    const PoseRefiner refiner(pile.scene, model.step, IcpParams{});
    for (const simulation::ObjectTruth& object : pile.truth.objects) {
      if (object.visible_fraction < 0.8) continue;
      const Eigen::Isometry3f truth = object.T_camera_object.cast<float>();
      const IcpResult icp = refiner.refine(model, truth);
      drift_mm.push_back(1000.0 * testing::translationError(icp.T_camera_model, truth));
      EXPECT_LT(testing::rotationErrorDeg(icp.T_camera_model.linear(), truth.linear()), 3.0);
    }
  }
  ASSERT_GE(drift_mm.size(), 6u);
  std::sort(drift_mm.begin(), drift_mm.end());
  EXPECT_LT(drift_mm[drift_mm.size() / 2], 0.5);  // median
  EXPECT_LT(drift_mm.back(), 3.0);
}

}  // namespace
}  // namespace binpick::estimation
