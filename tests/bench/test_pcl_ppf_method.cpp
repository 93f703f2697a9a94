// PCL's PPFRegistration wrapped as a benchmark method (bench/paper/pcl_ppf_method.hpp): on a small
// simulated pile it finds parts within the paper's thresholds (diam/10, 10 degrees), which fails
// if the poses were inverted (model-in-camera vs camera-in-model) or in the wrong unit; empty and
// NaN-only scenes give no poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bench_test_support.hpp"
#include "binpick/estimation/detector.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "experiment.hpp"
#include "pcl_ppf_method.hpp"
#include "thrown_message.hpp"

namespace binpick::bench {
namespace {

// PCL's PPFHashMapSearch inserts the N^2 model pairs into an unordered_multimap whose hash
// (XOR of the four shifted bin indices) takes under 500 values, so building it costs about
// O(N^4): 100 s for binpick's l_bracket model (tau_d = 0.04, 878 points). The tests use a coarser
// model (tau_d = 0.06, 458 points, about 8 s; at 0.07 PCL finds no part of this pile). The
// 20-object timing uses binpick's.
constexpr float kTestSamplingRatio = 0.06f;

struct Pile {
  simulation::Part part;
  estimation::PreparedModel model;
  simulation::PileParams params;
  simulation::PileScene scene;
};

// A pile of l_brackets and the part's prepared model.
Pile makePile(int objects, uint64_t seed, double depth_noise, float sampling_ratio) {
  Pile pile;
  pile.part = simulation::makePart("l_bracket");
  estimation::ModelParams model_params;
  model_params.sampling_ratio = sampling_ratio;
  pile.model = estimation::prepareModel(io::ModelGeometry{pile.part.mesh, {}}, model_params);
  pile.params.objects = objects;
  pile.params.seed = seed;
  pile.params.depth_noise = depth_noise;
  pile.scene = simulation::generatePile(pile.part.mesh, pile.params);
  return pile;
}

const Pile& smallPile() {
  static const Pile pile = makePile(4, 3, 0.0, kTestSamplingRatio);
  return pile;
}

evaluation::Score score(const Pile& pile, const std::vector<Eigen::Isometry3f>& poses) {
  return scorePoses(poses, pile.scene.objects, pile.part, pile.model.diameter);
}

MethodSetup setupFor(const Pile& pile) {
  MethodSetup setup;
  setup.model = &pile.model;
  setup.max_objects = pile.params.objects;
  return setup;
}

// Built once: the PCL hash map is the slow part of the tests.
const PclPpfMethod& smallPileMethod() {
  static const PclPpfMethod method(setupFor(smallPile()));
  return method;
}

// The origin of the nearest true part, and its distance from the pose's origin.
double distanceToNearestPart(const Pile& pile, const Eigen::Isometry3f& pose) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const simulation::ObjectTruth& object : pile.scene.objects) {
    nearest = std::min(nearest, (object.T_camera_object.translation() - pose.translation().cast<double>()).norm());
  }
  return nearest;
}

// Measured on this pile: 4 poses, 1 of the 4 findable parts found (the first pose, within 0.6 mm
// and 0.4 degree); the other three poses sit on their parts (origins 11 to 19 mm off) but turned
// 95 to 180 degrees. Those three parts lie flat and show one or two planes, which PCL's votes
// place wrongly even when each is alone in the scene; binpick's own detector finds 2 of the 4.
// So the bar: the first pose is right and every pose lies on a part (origin within diam/2 of a
// true origin). Inverted poses (camera in model) or millimetres for metres fail both.
TEST(PclPpfMethod, FindsAPartOfASmallPileAndEveryPoseLiesOnAPart) {
  const Pile& pile = smallPile();
  const MethodInput input{&pile.scene.cloud, evaluation::binInterior(pile.scene, pile.params)};
  EXPECT_EQ(smallPileMethod().name(), "pcl_ppf");
  const std::vector<Eigen::Isometry3f> poses = smallPileMethod().detect(input);
  const evaluation::Score s = score(pile, poses);
  ASSERT_EQ(s.findable, 4) << describeScore(s, poses.size());
  ASSERT_FALSE(poses.empty());
  EXPECT_LE(poses.size(), static_cast<std::size_t>(pile.params.objects));
  EXPECT_GE(s.found, 1) << describeScore(s, poses.size());
  EXPECT_GE(s.matched_object.front(), 0) << "the best pose is wrong: " << describeScore(s, poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT(distanceToNearestPart(pile, poses[i]), pile.model.diameter / 2.0) << "pose " << i;
  }
}

TEST(PclPpfMethod, NanOnlyAndEmptyCloudsGiveNoPoses) {
  const Pile& pile = smallPile();
  const PclPpfMethod& method = smallPileMethod();
  const estimation::CropBox crop = evaluation::binInterior(pile.scene, pile.params);

  testing::expectNoPosesWithoutPoints(method, crop);
  std::vector<Eigen::Isometry3f> poses;

  // Real points, all outside the crop box.
  estimation::CropBox nowhere = crop;
  nowhere.T_camera_box.translation() += Eigen::Vector3f(0.0f, 0.0f, -10.0f);
  EXPECT_NO_THROW(poses = method.detect(MethodInput{&pile.scene.cloud, nowhere}));
  EXPECT_TRUE(poses.empty());
}

TEST(PclPpfMethod, RejectsAMissingModelAndBadParams) {
  EXPECT_TRUE(test::throwsNaming([] { PclPpfMethod method(MethodSetup{}); }, "prepared model"));
  PclPpfParams params;
  params.reference_fraction = 0.0f;
  EXPECT_TRUE(test::throwsNaming([&] { PclPpfMethod method(setupFor(smallPile()), params); }, "reference_fraction"));
}

}  // namespace
}  // namespace binpick::bench
