// The scene voxel grid (eq. 3) and the verification score (eq. 4) on constructed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>

#include "estimation_test_support.hpp"
#include "verification.hpp"
#include "voxel_grid.hpp"

namespace binpick::estimation {
namespace {

using testing::errorMessage;
using testing::randomPose;

constexpr float kL = 0.002f;  // voxel side

TEST(SceneVoxelGrid, NeighbourhoodOfEachPointReturnsItsIndex) {
  // Points ten voxels apart or more: their 3x3x3 neighbourhoods never overlap.
  const std::vector<Eigen::Vector3f> points{
      {0.10f, 0.20f, 0.80f}, {0.13f, 0.20f, 0.80f}, {0.10f, 0.25f, 0.81f}, {0.0503f, 0.1f, 0.9f}};
  const SceneVoxelGrid grid(points, kL);
  EXPECT_EQ(grid.voxelSize(), kL);
  for (int32_t i = 0; i < static_cast<int32_t>(points.size()); ++i) {
    SCOPED_TRACE(i);
    // Less than one voxel along each axis: at most the adjacent voxel, whatever the alignment.
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3f q = points[i] + 0.99f * kL * Eigen::Vector3f(dx, dy, dz);
          EXPECT_EQ(grid.at(q), i) << "offset " << dx << " " << dy << " " << dz;
        }
    // Two or more voxels away along any axis: outside the neighbourhood.
    for (float far : {2.05f, 3.0f, 5.0f}) {
      for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {-1.0f, 1.0f}) {
          Eigen::Vector3f q = points[i];
          q[axis] += sign * far * kL;
          EXPECT_EQ(grid.at(q), SceneVoxelGrid::kEmpty) << "axis " << axis << " at " << sign * far << " voxels";
        }
      }
    }
  }
  const float nan = std::nanf("");
  EXPECT_EQ(grid.at({nan, 0.2f, 0.8f}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(grid.at({0.1f, nan, 0.8f}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(grid.at({0.1f, 0.2f, nan}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(grid.at({-5.0f, -5.0f, -5.0f}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(grid.at({5.0f, 5.0f, 5.0f}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(grid.at({-std::numeric_limits<float>::infinity(), 0.2f, 0.8f}), SceneVoxelGrid::kEmpty);
}

// Queries that crash the grid would take the whole test binary down: they run in a child
// process (threadsafe style: a fresh re-execution, safe with the OpenMP threads of other tests),
// which must exit normally with 0.
class SceneVoxelGridDeathTest : public ::testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

TEST_F(SceneVoxelGridDeathTest, InfiniteOrHugeQueriesReturnEmpty) {
  const std::vector<Eigen::Vector3f> points{{0.10f, 0.20f, 0.80f}, {0.13f, 0.20f, 0.80f}};
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Eigen::Vector3f> queries{
      {inf, 0.2f, 0.8f}, {0.1f, inf, 0.8f}, {0.1f, 0.2f, inf}, {1e17f, 0.2f, 0.8f}, {0.1f, 0.2f, 3e16f}};
  for (const Eigen::Vector3f& q : queries) {
    EXPECT_EXIT(
        {
          const SceneVoxelGrid grid(points, kL);
          std::exit(grid.at(q) == SceneVoxelGrid::kEmpty ? 0 : 1);
        },
        ::testing::ExitedWithCode(0), "")
        << "query " << q.transpose() << " must give kEmpty, not crash";
  }
}

TEST_F(SceneVoxelGridDeathTest, NonFiniteScenePointsAreRejectedOrIgnored) {
  // Not a crash or a std::length_error: a core::Error, or a grid that works.
  const float inf = std::numeric_limits<float>::infinity();
  for (const Eigen::Vector3f& bad : {Eigen::Vector3f(inf, 0.2f, 0.8f), Eigen::Vector3f(std::nanf(""), 0.2f, 0.8f)}) {
    for (int position = 0; position < 2; ++position) {
      std::vector<Eigen::Vector3f> points{{0.10f, 0.20f, 0.80f}, {0.13f, 0.20f, 0.80f}};
      points[position] = bad;
      EXPECT_EXIT(
          {
            try {
              const SceneVoxelGrid grid(points, kL);
              std::exit(grid.at(points[1 - position]) == 1 - position ? 0 : 2);
            } catch (const core::Error&) {
              std::exit(0);
            }
          },
          ::testing::ExitedWithCode(0), "")
          << "scene point " << position << " = " << bad.transpose();
    }
  }
}

// A wavy 2.5-D surface of 3000 points over +-0.15 m, 0.8 m away, as a bin scene is.
std::vector<Eigen::Vector3f> wavySurface(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> xy(-0.15f, 0.15f);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 3000; ++i) {
    const float x = xy(rng), y = xy(rng);
    points.emplace_back(x, y, 0.8f + 0.03f * std::sin(20.0f * x) * std::cos(15.0f * y));
  }
  return points;
}

TEST(SceneVoxelGrid, RandomSurfaceSatisfiesTheNeighbourhoodContract) {
  // The grid answers "a scene point near here".
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<float> xy(-0.15f, 0.15f), jitter(-0.02f, 0.02f);
  const std::vector<Eigen::Vector3f> points = wavySurface(rng);
  const SceneVoxelGrid grid(points, kL);
  // Every returned point lies in the query's 3x3x3 neighbourhood: closer than 2 voxels per axis.
  for (const auto& p : points) {
    const int32_t s = grid.at(p);
    ASSERT_NE(s, SceneVoxelGrid::kEmpty);
    EXPECT_LT((points[s] - p).cwiseAbs().maxCoeff(), 2.0f * kL + 1e-6f);
  }
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3f q(xy(rng), xy(rng), 0.8f + jitter(rng));
    const int32_t s = grid.at(q);
    if (s != SceneVoxelGrid::kEmpty) {
      EXPECT_LT((points[s] - q).cwiseAbs().maxCoeff(), 2.0f * kL + 1e-6f);
    } else {
      // Empty: no point within one voxel along every axis (it would have written this voxel).
      for (const auto& p : points) ASSERT_FALSE((p - q).cwiseAbs().maxCoeff() < 0.999f * kL) << "missed a point";
    }
  }
}

// Verification looks up a pose's model points through one affine map into voxel coordinates: the
// same scene point as at(pose * m), but where rounding moves m across a voxel's border.
TEST(SceneVoxelGrid, APosesVoxelMapFindsWhatThePosedPointFinds) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<float> xy(-0.1f, 0.1f), local(-0.03f, 0.03f);
  const SceneVoxelGrid grid(wavySurface(rng), kL);
  const float nudge = 1e-3f * kL;
  int differing = 0, found = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Isometry3f pose = randomPose(rng, 0.0f);
    pose.translation() = Eigen::Vector3f(xy(rng), xy(rng), 0.8f);
    const Eigen::Affine3f to_voxels = grid.voxelMapOf(pose);
    for (int k = 0; k < 400; ++k) {
      const Eigen::Vector3f m(local(rng), local(rng), local(rng));
      const int32_t mapped = grid.atVoxelCoordinates(to_voxels * m);
      found += mapped != SceneVoxelGrid::kEmpty;
      if (mapped == grid.at(pose * m)) continue;
      ++differing;
      bool beside = false;  // what a point a thousandth of a voxel away finds
      for (int corner = 0; corner < 27 && !beside; ++corner) {
        const Eigen::Vector3f step(static_cast<float>(corner % 3 - 1), static_cast<float>(corner / 3 % 3 - 1),
                                   static_cast<float>(corner / 9 - 1));
        beside = grid.at(pose * m + nudge * step) == mapped;
      }
      EXPECT_TRUE(beside) << "trial " << trial << ", point " << k << ": " << mapped << " is not at the border";
    }
  }
  EXPECT_GT(found, 1000) << "the poses put their points on the surface";
  EXPECT_LE(differing, 20);  // of 20000 lookups
}

TEST(SceneVoxelGrid, EmptySceneAndBadSize) {
  const SceneVoxelGrid empty({}, kL);
  EXPECT_EQ(empty.at({0, 0, 0}), SceneVoxelGrid::kEmpty);
  EXPECT_EQ(empty.at({1, 1, 1}), SceneVoxelGrid::kEmpty);
  EXPECT_NE(errorMessage([] { SceneVoxelGrid({{0, 0, 0}}, 0.0f); }), "");
  EXPECT_NE(errorMessage([] { SceneVoxelGrid({{0, 0, 0}}, -1.0f); }), "");
  EXPECT_NE(errorMessage([] { SceneVoxelGrid({{0, 0, 0}}, std::nanf("")); }), "");
  // A scene spanning kilometres at a millimetre voxel would need too many blocks.
  EXPECT_NE(errorMessage([] { SceneVoxelGrid({{0, 0, 0}, {1000, 1000, 1000}}, 0.001f); }), "");
}

// A hand-built "model": ten points on a line, 10 mm apart (five voxels), normals along +z.
PreparedModel lineModel() {
  PreparedModel m;
  for (int k = 0; k < 10; ++k) {
    m.points.emplace_back(0.01f * k, 0.0f, 0.0f);
    m.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  m.diameter = 0.09f;
  m.step = 0.01f;
  return m;
}

class Eq4 : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937_64 rng(12);
    pose = randomPose(rng, 0.2f);
    pose.translation().z() += 0.8f;
    // The scene holds model points 0..5 at the pose (in reverse order, 0.3 mm off), plus two
    // distractors far from the line; points 6..9 of the model have nothing near them.
    for (int k = 5; k >= 0; --k) {
      scene_points.push_back(pose * (model.points[k] + Eigen::Vector3f(0.0003f, -0.0002f, 0.0001f)));
      scene_normals.push_back(pose.linear() * model.normals[k]);
    }
    scene_points.push_back(pose * Eigen::Vector3f(0.0f, 0.05f, 0.0f));
    scene_normals.push_back({0, 0, -1});
    scene_points.push_back(pose * Eigen::Vector3f(0.05f, 0.0f, 0.05f));
    scene_normals.push_back({0, 0, -1});
  }
  const PreparedModel model = lineModel();
  Eigen::Isometry3f pose;
  std::vector<Eigen::Vector3f> scene_points, scene_normals;
};

TEST_F(Eq4, SupportHoldsExactlyTheFittedModelPoints) {
  const SceneVoxelGrid grid(scene_points, kL);
  const std::vector<uint32_t> support = correspondingScenePoints(model, pose, grid, scene_normals, -2.0f);
  // Model point k (k <= 5) fits scene point 5 - k; in model order.
  EXPECT_EQ(support, (std::vector<uint32_t>{5, 4, 3, 2, 1, 0}));

  std::vector<uint8_t> exist(scene_points.size(), 1);
  EXPECT_EQ(existingCount(support, exist), 6u);
  exist[0] = 0;
  exist[3] = 0;
  exist[6] = 0;  // a distractor: not in the support, changes nothing
  EXPECT_EQ(existingCount(support, exist), 4u);
  std::fill(exist.begin(), exist.end(), 0);
  EXPECT_EQ(existingCount(support, exist), 0u);
  EXPECT_EQ(existingCount({}, exist), 0u);

  // Shifted by three voxels along the camera axis the line is most perpendicular to, nothing
  // fits: the own partner is 3 voxels off along that axis, the others > 2 voxels along another.
  const Eigen::Vector3f direction = pose.linear() * Eigen::Vector3f::UnitX();
  int axis = 0;
  direction.cwiseAbs().minCoeff(&axis);
  Eigen::Isometry3f away = pose;
  away.translation()[axis] += 3.0f * kL;
  EXPECT_TRUE(correspondingScenePoints(model, away, grid, scene_normals, -2.0f).empty());
}

TEST_F(Eq4, DuplicatesAreCountedPerModelPoint) {
  PreparedModel dense = model;
  dense.points.push_back(model.points[2] + Eigen::Vector3f(0.0005f, 0.0f, 0.0f));
  dense.normals.emplace_back(0.0f, 0.0f, 1.0f);
  const SceneVoxelGrid grid(scene_points, kL);
  const auto support = correspondingScenePoints(dense, pose, grid, scene_normals, -2.0f);
  EXPECT_EQ(support, (std::vector<uint32_t>{5, 4, 3, 2, 1, 0, 3}));
  std::vector<uint8_t> exist(scene_points.size(), 1);
  exist[3] = 0;
  EXPECT_EQ(existingCount(support, exist), 5u) << "both model points on scene point 3 stop counting";
}

TEST_F(Eq4, NormalGateDropsOpposingSurfaces) {
  scene_normals[1] = -scene_normals[1];  // model point 4's partner faces the other way
  scene_normals[4] = (pose.linear() * Eigen::Vector3f(0.0f, 1.0f, 0.0f));  // 90 degrees off
  const SceneVoxelGrid grid(scene_points, kL);
  EXPECT_EQ(correspondingScenePoints(model, pose, grid, scene_normals, -2.0f).size(), 6u) << "gate off";
  EXPECT_EQ(correspondingScenePoints(model, pose, grid, scene_normals, 0.5f), (std::vector<uint32_t>{5, 3, 2, 0}));
  EXPECT_EQ(correspondingScenePoints(model, pose, grid, scene_normals, -0.5f), (std::vector<uint32_t>{5, 4, 3, 2, 0}));

  // verify() with the gate at 60 degrees gives the same, per candidate, with score = |support|.
  PreparedScene scene;
  scene.points = scene_points;
  scene.normals = scene_normals;
  std::vector<PoseCandidate> candidates(2);
  candidates[0].T_camera_model = pose;
  candidates[0].votes = 17;
  candidates[1].T_camera_model = pose;
  candidates[1].T_camera_model.translation().x() += 1.0f;
  VerificationParams params;
  params.max_normal_angle_deg = 60.0f;
  const auto verified = verify(candidates, model, scene, grid, params, nullptr, 2);
  ASSERT_EQ(verified.size(), 2u);
  EXPECT_EQ(verified[0].support, (std::vector<uint32_t>{5, 3, 2, 0}));
  EXPECT_EQ(verified[0].score, 4u);
  EXPECT_EQ(verified[0].votes, 17u);
  EXPECT_TRUE(verified[0].T_camera_model.matrix() == pose.matrix());
  EXPECT_TRUE(verified[1].support.empty());
  EXPECT_EQ(verified[1].score, 0u);
  params.max_normal_angle_deg = 180.0f;
  EXPECT_EQ(verify(candidates, model, scene, grid, params)[0].score, 6u);
}

}  // namespace
}  // namespace binpick::estimation
