// Symmetric models reduced: a part that maps onto itself turned about an axis votes from the model
// points of one turn only (ModelSymmetry). The table shrinks by the symmetry and the same parts are
// found, as well, on a pile.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/pile.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;

PreparedModel unreduced(const std::string& part) {
  ModelParams params;
  params.reduce_by_symmetry = false;
  return prepareModel(io::ModelGeometry{simulation::makePart(part).mesh, {}}, params);
}

bool lessXyz(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The same model points, only in another order.
void expectSamePoints(std::vector<Eigen::Vector3f> a, std::vector<Eigen::Vector3f> b) {
  std::sort(a.begin(), a.end(), lessXyz);
  std::sort(b.begin(), b.end(), lessXyz);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(a[k] == b[k]) << "point " << k;
}

// The azimuth about `axis`, radians in [0, 2 pi).
float azimuth(const Eigen::Vector3f& p, const Eigen::Vector3f& axis) {
  const Eigen::Vector3f u = axis.unitOrthogonal(), v = axis.cross(u);
  const float a = std::atan2(p.dot(v), p.dot(u));
  return a < 0.0f ? a + 2.0f * static_cast<float>(M_PI) : a;
}

// The gear turns onto itself every 30 degrees about its axis and flips over: its references are
// the upper half of a 30-degree sector, a 24th of its points (and the margins at their edges).
TEST(SymmetricModel, AGearVotesFromOneTwentyFourthOfItsPoints) {
  const PreparedModel& gear = cachedModel("gear");
  const PreparedModel full = unreduced("gear");
  EXPECT_EQ(gear.symmetry.describe(), "12-fold about (0, 0, 1), flips over");
  expectSamePoints(gear.points, full.points);
  EXPECT_EQ(full.referenceCount(), full.size());
  EXPECT_GT(gear.referenceCount(), gear.size() / 24);
  EXPECT_LT(gear.referenceCount(), gear.size() / 12);
  EXPECT_LT(gear.table.pairCount(), full.table.pairCount() / 12);
  for (std::size_t k = 0; k < gear.referenceCount(); ++k) {
    const Eigen::Vector3f& p = gear.points[k];
    const Eigen::Vector3f& axis = gear.symmetry.axis;
    const float radius = (p - p.dot(axis) * axis).norm();
    EXPECT_LT(radius * (azimuth(p, axis) - static_cast<float>(M_PI / 6.0)), 0.51f * gear.step) << "point " << k;
    EXPECT_GT(p.dot(axis), -0.51f * gear.step) << "point " << k;
  }
  for (const PairEntry& e : gear.table.entries()) ASSERT_LT(e.reference, gear.referenceCount());
}

TEST(SymmetricModel, ARevolvedPartVotesFromAStripAlongOneMeridian) {
  const PreparedModel& ring = cachedModel("ring_magnet");
  EXPECT_EQ(ring.symmetry.turns, 0) << ring.symmetry.describe();
  EXPECT_LT(ring.referenceCount(), ring.size() / 5);
  EXPECT_GT(ring.referenceCount(), 0u);
}

TEST(SymmetricModel, APartWithoutSymmetryKeepsEveryReferenceInItsOrder) {
  const PreparedModel& bracket = cachedModel("l_bracket");
  const PreparedModel full = unreduced("l_bracket");
  EXPECT_EQ(bracket.symmetry.turns, 1);
  EXPECT_EQ(bracket.symmetry.describe(), "none");
  EXPECT_EQ(bracket.referenceCount(), bracket.size());
  EXPECT_TRUE(bracket.points == full.points);
  EXPECT_EQ(bracket.table.pairCount(), full.table.pairCount());
}

// On a pile of gears the reduced model finds at least the parts the full one finds, and its first
// picks are right.
TEST(SymmetricModel, TheReducedGearFindsThePartsTheFullOneFinds) {
  simulation::PileParams pile;
  pile.objects = 10;
  pile.seed = 21;
  pile.bin_length = 0.24;
  pile.bin_width = 0.18;
  const simulation::Part part = simulation::makePart("gear");
  const simulation::PileScene scene = simulation::generatePile(part.mesh, pile);
  DetectorParams params;
  params.selection.max_objects = pile.objects;
  params.scene.crop = evaluation::binInterior(scene, pile);
  params.threads = 2;
  const auto found = [&](const PreparedModel& model) {
    const DetectionResult result = Detector(model, params).detect(scene.cloud);
    return evaluation::scoreDetections(result.detections, scene.objects, part.symmetry, {model.diameter / 10.0, 10.0});
  };
  const evaluation::Score reduced = found(cachedModel("gear"));
  const evaluation::Score full = found(unreduced("gear"));
  ASSERT_GT(full.findable, 3);
  EXPECT_GE(reduced.found, full.found);
  EXPECT_EQ(reduced.wrong_in_first_10, 0);
}

}  // namespace
}  // namespace binpick::estimation
