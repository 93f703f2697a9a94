// ICP on visible model points (section III-D) on a rendered view of a single part.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "binpick/estimation/icp.hpp"
#include "binpick/estimation/scene.hpp"
#include "binpick/simulation/pile.hpp"
#include "estimation_test_support.hpp"
#include "evaluation.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;
using testing::perturbed;
using testing::rotationErrorDeg;
using testing::translationError;

struct SinglePart {
  const PreparedModel* model = nullptr;
  sim::PileScene pile;
  PreparedScene scene;
  Eigen::Isometry3f truth;
};

SinglePart renderSinglePart(const std::string& part, uint64_t seed) {
  SinglePart s;
  s.model = &cachedModel(part);
  sim::PileParams params;
  params.objects = 1;
  params.depth_noise = 0.0;
  params.seed = seed;
  s.pile = sim::generatePile(sim::makePart(part).mesh, params);
  SceneParams scene_params;
  scene_params.crop = eval::binInterior(s.pile, params);
  s.scene = prepareScene(s.pile.cloud, *s.model, scene_params);
  s.truth = s.pile.objects.at(0).T_camera_object.cast<float>();
  return s;
}

class IcpOnSinglePart : public ::testing::TestWithParam<std::string> {};

TEST_P(IcpOnSinglePart, ConvergesFromAPerturbedPose) {
  const SinglePart s = renderSinglePart(GetParam(), 3);
  ASSERT_GT(s.scene.size(), 50u);
  const PoseRefiner refiner(s.scene, s.model->step, IcpParams{});
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    SCOPED_TRACE(trial);
    const Eigen::Isometry3f initial = perturbed(s.truth, rng, 0.005f, 5.0f);
    ASSERT_GT(rotationErrorDeg(initial.linear(), s.truth.linear()), 4.9);
    const IcpResult r = refiner.refine(*s.model, initial);
    EXPECT_LT(translationError(r.T_camera_model, s.truth), 0.001);
    EXPECT_LT(rotationErrorDeg(r.T_camera_model.linear(), s.truth.linear()), 0.5);
    EXPECT_GT(r.iterations, 0);
    EXPECT_GT(r.coverage, 0.8f);
    EXPECT_GT(r.visible_points, 0);
    EXPECT_LT(r.rmse, 0.25f * s.model->step);
    // The refined rotation is orthonormal.
    const Eigen::Matrix3f R = r.T_camera_model.linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3f::Identity()).norm(), 1e-5f);
  }
}

TEST_P(IcpOnSinglePart, VisibleModelPointsFaceTheCameraAndAreSeen) {
  const SinglePart s = renderSinglePart(GetParam(), 4);
  const PreparedModel& model = *s.model;
  const std::vector<uint32_t> visible = visibleModelPoints(model, s.truth);
  ASSERT_FALSE(visible.empty());
  EXPECT_LT(visible.size(), model.size());
  EXPECT_LT(visible.size(), model.size() * 3 / 4) << "a camera sees at most about half of a part";
  EXPECT_EQ(std::set<uint32_t>(visible.begin(), visible.end()).size(), visible.size()) << "no repeats";
  std::size_t facing = 0;
  for (uint32_t k = 0; k < model.size(); ++k) {
    const Eigen::Vector3f p = s.truth * model.points[k];
    facing += (s.truth.linear() * model.normals[k]).dot(p) < 0.0f;
  }
  std::size_t seen = 0;
  for (uint32_t k : visible) {
    ASSERT_LT(k, model.size());
    const Eigen::Vector3f p = s.truth * model.points[k];
    EXPECT_LT((s.truth.linear() * model.normals[k]).dot(p), 0.0f) << "model point " << k << " faces away";
    // The rendered view shows the visible points: a scene point lies within a step.
    float nearest = std::numeric_limits<float>::infinity();
    for (const auto& q : s.scene.points) nearest = std::min(nearest, (q - p).norm());
    seen += nearest < model.step;
  }
  EXPECT_LE(visible.size(), facing);
  EXPECT_GT(seen, visible.size() * 9 / 10) << seen << " of " << visible.size() << " visible points are in the view";

  // Turned half a turn about the viewing axis through the part, the camera sees the same faces;
  // turned over (half a turn about x), the other side.
  Eigen::Isometry3f over = s.truth;
  over.linear() = Eigen::AngleAxisf(static_cast<float>(testing::kPi), Eigen::Vector3f::UnitX()) * s.truth.linear();
  const std::vector<uint32_t> other = visibleModelPoints(model, over);
  std::size_t shared = 0;
  const std::set<uint32_t> first(visible.begin(), visible.end());
  for (uint32_t k : other) shared += first.count(k);
  EXPECT_LT(shared, visible.size() / 4) << "the far side is mostly other points";

  // Behind the camera nothing is visible.
  Eigen::Isometry3f behind = s.truth;
  behind.translation().z() = -1.0f;
  EXPECT_TRUE(visibleModelPoints(model, behind).empty());
}

INSTANTIATE_TEST_SUITE_P(Parts, IcpOnSinglePart, ::testing::Values("l_bracket", "clamp"),
                         [](const ::testing::TestParamInfo<std::string>& part) { return part.param; });

TEST(PoseRefiner, EmptySceneLeavesThePose) {
  const PreparedModel& model = testing::smallModel();
  const PreparedScene empty;
  const PoseRefiner refiner(empty, model.step, IcpParams{});
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() << 0.01f, 0.02f, 0.8f;
  const IcpResult r = refiner.refine(model, pose);
  EXPECT_TRUE(r.T_camera_model.isApprox(pose));
  EXPECT_EQ(r.iterations, 0);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.coverage, 0.0f);
}

}  // namespace
}  // namespace binpick::estimation
