// ICP on visible model points (section III-D) on a rendered view of a single part.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <random>
#include <set>

#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "binpick/simulation/virtual_rig.hpp"
#include "estimation_test_support.hpp"
#include "icp.hpp"
#include "kdtree.hpp"
#include "scene.hpp"

namespace binpick::estimation {
namespace {

using testing::cachedModel;
using testing::perturbed;
using testing::rotationErrorDeg;
using testing::translationError;

struct SinglePart {
  const PreparedModel* model = nullptr;
  PreparedScene scene;
  Eigen::Isometry3f truth;
};

// How well a view pins a pose down by point-to-plane distances: the smallest over the largest
// eigenvalue of the information matrix (rotations about the centroid scaled by `radius`).
double viewConditioning(const PreparedScene& scene, double radius) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : scene.points) centre += p.cast<double>();
  centre /= static_cast<double>(std::max<std::size_t>(scene.size(), 1));
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < scene.size(); ++i) {
    const Eigen::Vector3d n = scene.normals[i].cast<double>();
    Eigen::Matrix<double, 6, 1> j;
    j << (scene.points[i].cast<double>() - centre).cross(n) / radius, n;
    information += j * j.transpose();
  }
  const auto eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(information).eigenvalues();
  return eigenvalues.minCoeff() / eigenvalues.maxCoeff();
}

// The part alone, 0.85 m in front of the camera at a random (seeded) attitude, every surface the
// camera sees. Attitudes are drawn until the view constrains all six degrees of freedom (a part
// showing one face, like one lying flat in a bin, leaves it free to slide: no ICP can converge
// there, and that is not what this checks).
SinglePart renderSinglePart(const std::string& part, uint64_t seed) {
  SinglePart s;
  s.model = &cachedModel(part);
  const simulation::Part built = simulation::makePart(part);
  const io::RigCalibration rig = simulation::makeVirtualRig();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int attempt = 0; attempt < 50; ++attempt) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.02, -0.01, 0.85);
    const simulation::RayCaster caster({{&built.mesh, pose, 0}});
    const simulation::SensorGeometry geometry = simulation::computeSensorGeometry(rig, caster);
    io::PointCloud cloud;
    cloud.width = geometry.width;
    cloud.height = geometry.height;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    cloud.points.assign(geometry.point.size(), Eigen::Vector3f(nan, nan, nan));
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      if (geometry.camera_cosine[i] > 0.0f) cloud.points[i] = geometry.point[i];
    }
    s.scene = prepareScene(cloud, *s.model, SceneParams{});
    s.truth = pose.cast<float>();
    if (viewConditioning(s.scene, 0.5 * s.model->diameter) > 0.02) break;
  }
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
    EXPECT_GT(r.fit.coverage(), 0.8f);
    EXPECT_GT(r.fit.visible, 0);
    EXPECT_LT(r.fit.rmse, 0.25f * s.model->step);
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

// The pick's correspondences are searched on every thread; the pose must not depend on how many.
TEST_P(IcpOnSinglePart, OneThreadAndTwoRefineToTheSamePose) {
  const SinglePart s = renderSinglePart(GetParam(), 3);
  const PoseRefiner serial(s.scene, s.model->step, IcpParams{}, 1);
  const PoseRefiner shared(s.scene, s.model->step, IcpParams{}, 2);
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Isometry3f initial = perturbed(s.truth, rng, 0.004f, 4.0f);
    const IcpResult a = serial.refine(*s.model, initial);
    const IcpResult b = shared.refine(*s.model, initial);
    EXPECT_EQ(a.iterations, b.iterations) << trial;
    EXPECT_TRUE(a.T_camera_model.matrix() == b.T_camera_model.matrix()) << trial;
    EXPECT_EQ(a.fit.fitted, b.fit.fitted) << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(Parts, IcpOnSinglePart, ::testing::Values("l_bracket", "clamp"),
                         [](const ::testing::TestParamInfo<std::string>& part) { return part.param; });

// ICP's gated search: the nearest point when it lies within the bound (the bound included),
// none otherwise; the same answer as searching the whole tree.
TEST(KdTreeSearch, NearestWithinABoundIsTheNearestOrNone) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::vector<Eigen::Vector3f> points(500);
  for (Eigen::Vector3f& p : points) p = Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng));
  const KdTree tree(points);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3f query(coordinate(rng), coordinate(rng), coordinate(rng));
    const auto [nearest, distance_sq] = tree.nearest(query);
    for (const float bound_sq : {0.5f * distance_sq, distance_sq, 2.0f * distance_sq}) {
      const auto [within, within_sq] = tree.nearestWithin(query, bound_sq);
      if (distance_sq <= bound_sq) {
        EXPECT_EQ(within, nearest) << q;
        EXPECT_EQ(within_sq, distance_sq) << q;
      } else {
        EXPECT_EQ(within, -1) << q;
      }
    }
  }
  EXPECT_EQ(KdTree(std::vector<Eigen::Vector3f>{}).nearestWithin(Eigen::Vector3f::Zero(), 1.0f).first, -1);
}

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
  EXPECT_EQ(r.fit.coverage(), 0.0f);
}

}  // namespace
}  // namespace binpick::estimation
