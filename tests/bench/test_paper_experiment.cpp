// The benchmark's experiment: scoring with the paper's criterion, the scenes both inputs come
// from, binpick on them, and Figure 5's selection strategies agreeing on their picks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bench_scenes.hpp"
#include "binpick/core/error.hpp"
#include "binpick_method.hpp"
#include "experiment.hpp"
#include "selection_timing.hpp"

namespace binpick::bench {
namespace {

const simulation::Part& lBracket() {
  static const simulation::Part part = simulation::makePart("l_bracket");
  return part;
}

const estimation::PreparedModel& lBracketModel() {
  static const estimation::PreparedModel model = estimation::prepareModel(io::ModelGeometry{lBracket().mesh, {}}, {});
  return model;
}

const BenchScene& exactScene() {
  static const BenchScene scene = [] {
    SceneRequest request;
    request.objects = 6;
    request.seed = 5;
    request.reconstruct = false;
    return makeBenchScene(lBracket(), request);
  }();
  return scene;
}

// Returns the true poses, each moved by `offset` (camera frame) and given `copies` times.
class TruthMethod : public PoseMethod {
 public:
  TruthMethod(const BenchScene& scene, Eigen::Vector3f offset, int copies)
      : scene_(scene), offset_(offset), copies_(copies) {}
  std::string name() const override { return "truth"; }
  std::vector<Eigen::Isometry3f> detect(const MethodInput&) const override {
    std::vector<Eigen::Isometry3f> poses;
    for (const simulation::ObjectTruth& object : scene_.truth.objects) {
      Eigen::Isometry3f pose = object.T_camera_object.cast<float>();
      pose.translation() += offset_;
      for (int c = 0; c < copies_; ++c) poses.push_back(pose);
    }
    return poses;
  }

 private:
  const BenchScene& scene_;
  Eigen::Vector3f offset_;
  int copies_;
};

SceneOutcome runTruth(Eigen::Vector3f offset, int copies) {
  const TruthMethod method(exactScene(), offset, copies);
  return runMethod(method, exactScene(), CloudInput::Exact, lBracket(), lBracketModel().diameter);
}

TEST(PaperExperiment, TruePosesAreAllCorrect) {
  const SceneOutcome o = runTruth(Eigen::Vector3f::Zero(), 1);
  Tally tally;
  tally.add(o);
  EXPECT_EQ(o.objects, 6);
  EXPECT_EQ(o.correct, 6);
  EXPECT_DOUBLE_EQ(tally.recognitionRate(), 1.0);
  EXPECT_DOUBLE_EQ(tally.precision(), 1.0);
  EXPECT_DOUBLE_EQ(tally.recall(), 1.0);
  EXPECT_GT(o.input_points, 10000u);
}

TEST(PaperExperiment, RepeatedPosesOfAnObjectAreWrong) {
  const SceneOutcome o = runTruth(Eigen::Vector3f::Zero(), 2);
  Tally tally;
  tally.add(o);
  EXPECT_EQ(o.detections, 12);
  EXPECT_EQ(o.correct, 6);
  EXPECT_DOUBLE_EQ(tally.precision(), 0.5);
  EXPECT_DOUBLE_EQ(tally.recognitionRate(), 1.0);
}

TEST(PaperExperiment, TranslationCriterionIsATenthOfTheDiameter) {
  const float tenth = lBracketModel().diameter / 10.0f;
  EXPECT_EQ(runTruth(Eigen::Vector3f(0.9f * tenth, 0.0f, 0.0f), 1).correct, 6);
  EXPECT_EQ(runTruth(Eigen::Vector3f(0.0f, 1.1f * tenth, 0.0f), 1).correct, 0);
}

TEST(PaperExperiment, BinpickFindsTheHalfVisibleObjectsOfTheExactCloud) {
  const MethodSetup setup{&lBracketModel(), 6, 0, {}};
  const auto method = makeBinpickMethod("binpick", setup);
  const SceneOutcome o = runMethod(*method, exactScene(), CloudInput::Exact, lBracket(), lBracketModel().diameter);
  ASSERT_TRUE(o.stages.has_value());
  EXPECT_GT(o.stages->total, 0.0);
  // Six L brackets lying mostly flat in the default bin; the first picks are the clearest ones.
  EXPECT_GE(2 * o.found, o.findable) << o.found << " of " << o.findable;
  EXPECT_GE(2 * o.correct, o.detections) << o.correct << " of " << o.detections;
}

TEST(PaperExperiment, DrostBaselinesFollowTableOne) {
  const MethodSetup setup{&lBracketModel(), 6, 0, {}};
  EXPECT_EQ(makeBinpickMethod("ppf1", setup)->name(), "ppf1");
  EXPECT_EQ(makeBinpickMethod("ppf5", setup)->name(), "ppf5");
  EXPECT_THROW(makeBinpickMethod("ppf3", setup), core::Error);
}

TEST(BenchScenes, TheReconstructedCloudLiesOnTheExactOne) {
  SceneRequest request;
  request.objects = 4;
  request.seed = 2;
  const BenchScene scene = makeBenchScene(lBracket(), request);
  ASSERT_EQ(scene.reconstructed.size(), scene.truth.cloud.size());
  const MethodInput exact{&scene.truth.cloud, scene.crop}, reconstructed{&scene.reconstructed, scene.crop};
  EXPECT_GT(croppedPoints(reconstructed).size(), croppedPoints(exact).size() * 8 / 10);
  std::vector<float> dz;
  for (std::size_t i = 0; i < scene.reconstructed.size(); ++i) {
    const Eigen::Vector3f& a = scene.reconstructed.points[i];
    const Eigen::Vector3f& b = scene.truth.cloud.points[i];
    if (a.allFinite() && b.allFinite() && scene.crop.contains(b)) dz.push_back(std::abs(a.z() - b.z()));
  }
  ASSERT_FALSE(dz.empty());
  std::nth_element(dz.begin(), dz.begin() + dz.size() / 2, dz.end());
  EXPECT_LT(dz[dz.size() / 2], 0.001f);  // median under a millimetre
  EXPECT_GT(scene.reconstruct_ms, 0.0);
}

TEST(SelectionStrategies, AllThreePickTheSamePosesInTheSameOrder) {
  const SelectionCurves c = measureSelection(lBracketModel(), exactScene().truth.cloud, exactScene().crop, 6, 0);
  EXPECT_GT(c.candidates, 100u);
  ASSERT_EQ(c.algorithm1_picks.size(), 6u);
  EXPECT_EQ(c.rescore_all_picks, c.algorithm1_picks);
  EXPECT_EQ(c.reverify_all_picks, c.algorithm1_picks);
  ASSERT_EQ(c.algorithm1_ms.size(), 6u);
  EXPECT_TRUE(std::is_sorted(c.algorithm1_ms.begin(), c.algorithm1_ms.end()));  // cumulative
}

}  // namespace
}  // namespace binpick::bench
