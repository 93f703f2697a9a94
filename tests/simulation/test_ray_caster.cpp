#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/ray_caster.hpp"
#include "mesh_test_utils.hpp"
#include "render_test_utils.hpp"

namespace binpick::simulation {
namespace {

using test::boxMesh;
using test::pose;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const Eigen::Vector3d kHalf(0.10, 0.05, 0.02);

Eigen::Isometry3d tiltedPose() {
  return pose(Eigen::Vector3d(0.05, -0.02, 1.0), Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
}

Ray rayBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  Ray ray;
  ray.origin = from;
  ray.direction = (to - from).normalized();
  return ray;
}

TEST(RayCaster, BoxMeshIsClosedWithOutwardWinding) {
  const io::TriangleMesh box = boxMesh(kHalf);
  EXPECT_EQ(test::closedManifoldProblem(box), "");
  EXPECT_NEAR(test::signedVolume(box), 8.0 * kHalf.prod(), 1e-9);
}

// Points on every face of a box at a tilted pose, hit from outside along skew directions.
TEST(RayCaster, HitsOnEveryBoxFaceMatchTheAnalyticGeometry) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const Eigen::Isometry3d T = tiltedPose();
  const RayCaster caster({{&box, T, 42}});
  int checked = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      Eigen::Vector3d local_normal = Eigen::Vector3d::Zero();
      local_normal[axis] = sign;
      for (double a : {-0.7, 0.1, 0.55}) {
        for (double b : {-0.4, 0.35}) {
          Eigen::Vector3d local = local_normal.cwiseProduct(kHalf);
          local[(axis + 1) % 3] = a * kHalf[(axis + 1) % 3];
          local[(axis + 2) % 3] = b * kHalf[(axis + 2) % 3];
          // From the open half-space outside the face, the box (convex) is first met at `local`.
          const Eigen::Vector3d local_origin =
              local + 0.3 * (local_normal + Eigen::Vector3d(0.2, -0.3, 0.25)).normalized();
          const double expected_t = (local - local_origin).norm();
          const RayHit hit = caster.closestHit(rayBetween(T * local_origin, T * local));
          ASSERT_TRUE(hit.hit());
          EXPECT_NEAR(hit.t, expected_t, 1e-6);
          EXPECT_LT((hit.point - T * local).norm(), 1e-5);
          EXPECT_LT((hit.object_point - local).norm(), 1e-5);
          EXPECT_LT((hit.normal - T.linear() * local_normal).norm(), 1e-9);
          EXPECT_EQ(hit.object_id, 42);
          EXPECT_EQ(hit.object_index, 0);
          ASSERT_GE(hit.triangle, 0);
          ASSERT_LT(hit.triangle, 12);
          // The triangle reported lies on that face.
          for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d corner = box.vertices[box.triangles[hit.triangle][k]].cast<double>();
            EXPECT_NEAR(corner.dot(local_normal), kHalf[axis], 1e-6);
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 36);
}

TEST(RayCaster, RangeLimitsSelectTheFaceAndNormalsStayOutward) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster({{&box, pose(Eigen::Vector3d(0, 0, 1.0)), 1}});
  Ray ray;  // from the camera along +z: the -z face at 0.98, the +z face at 1.02
  EXPECT_NEAR(caster.closestHit(ray).t, 0.98, 1e-9);
  ray.t_max = 0.97;
  EXPECT_FALSE(caster.closestHit(ray).hit());
  EXPECT_FALSE(caster.occluded(ray));
  ray.t_max = 0.99;
  EXPECT_TRUE(caster.occluded(ray));
  ray.t_min = 0.99;
  ray.t_max = kInf;
  const RayHit far = caster.closestHit(ray);
  ASSERT_TRUE(far.hit());
  EXPECT_NEAR(far.t, 1.02, 1e-9);
  // The far face is met from inside: its normal still points out of the box, along the ray.
  EXPECT_LT((far.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  ray.t_min = 1.03;
  EXPECT_FALSE(caster.closestHit(ray).hit());
  EXPECT_FALSE(caster.occluded(ray));
}

TEST(RayCaster, DirectionNeedNotBeUnitAndMissesReportNothing) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster({{&box, pose(Eigen::Vector3d(0, 0, 1.0)), 1}});
  Ray ray;
  ray.direction = Eigen::Vector3d(0, 0, 5.0);
  EXPECT_NEAR(caster.closestHit(ray).t, 0.98, 1e-9);
  ray.direction = Eigen::Vector3d(0, 0, -1.0);
  const RayHit miss = caster.closestHit(ray);
  EXPECT_FALSE(miss.hit());
  EXPECT_EQ(miss.object_id, -1);
  EXPECT_EQ(miss.object_index, -1);
  EXPECT_EQ(miss.triangle, -1);
  EXPECT_TRUE(std::isinf(miss.t));
  EXPECT_TRUE(miss.point.array().isNaN().all());
}

TEST(RayCaster, InstancesOfOneMeshKeepTheirIdsAndTheMeshNeedNotOutliveTheCaster) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 5; ++i) poses.push_back(pose(Eigen::Vector3d(0.3 * (i - 2), 0.0, 1.0)));
  std::unique_ptr<RayCaster> caster;
  {
    const io::TriangleMesh box = boxMesh(kHalf);
    std::vector<RenderObject> objects;
    for (int i = 0; i < 5; ++i) objects.push_back({&box, poses[i], 100 + i});
    caster = std::make_unique<RayCaster>(objects);
  }
  ASSERT_EQ(caster->objectCount(), 5);
  for (int i = 0; i < 5; ++i) {
    const RayHit hit =
        caster->closestHit(rayBetween(Eigen::Vector3d::Zero(), poses[i] * Eigen::Vector3d(0.01, 0.01, 0.0)));
    ASSERT_TRUE(hit.hit());
    EXPECT_EQ(hit.object_index, i);
    EXPECT_EQ(hit.object_id, 100 + i);
    EXPECT_EQ(caster->objectId(i), 100 + i);
    EXPECT_NEAR(hit.object_point.z(), -kHalf.z(), 1e-6);
    EXPECT_TRUE(caster->objectPose(i).isApprox(poses[i]));
    EXPECT_TRUE(caster->objectBounds(i).contains(poses[i].translation()));
  }
}

TEST(RayCaster, AloneQueriesIgnoreTheOtherObjects) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster({{&box, pose(Eigen::Vector3d(0, 0, 0.5)), 7}, {&box, pose(Eigen::Vector3d(0, 0, 1.0)), 8}});
  Ray ray;
  EXPECT_EQ(caster.closestHit(ray).object_id, 7);
  const RayHit back = caster.closestHitAlone(1, ray);
  ASSERT_TRUE(back.hit());
  EXPECT_EQ(back.object_id, 8);
  EXPECT_EQ(back.object_index, 1);
  EXPECT_NEAR(back.t, 0.98, 1e-9);
  ray.t_min = 0.6;
  ray.t_max = 0.9;
  EXPECT_FALSE(caster.occludedAlone(1, ray));
  EXPECT_FALSE(caster.occluded(ray));
  ray.t_max = 1.5;
  EXPECT_TRUE(caster.occludedAlone(1, ray));
  EXPECT_FALSE(caster.occludedAlone(0, ray));
  EXPECT_THROW(caster.closestHitAlone(2, ray), core::Error);
  EXPECT_THROW(caster.occludedAlone(-1, ray), core::Error);
  EXPECT_THROW(caster.objectBounds(2), core::Error);
}

TEST(RayCaster, EmptySceneAndEmptyMeshesAreNeverHit) {
  const RayCaster nothing({});
  Ray ray;
  EXPECT_EQ(nothing.objectCount(), 0);
  EXPECT_FALSE(nothing.closestHit(ray).hit());
  EXPECT_FALSE(nothing.occluded(ray));

  const io::TriangleMesh empty;
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster mixed({{&empty, pose(Eigen::Vector3d(0, 0, 0.5)), 1}, {&box, pose(Eigen::Vector3d(0, 0, 1)), 2}});
  EXPECT_EQ(mixed.closestHit(ray).object_index, 1);
  EXPECT_FALSE(mixed.closestHitAlone(0, ray).hit());
  EXPECT_FALSE(mixed.occludedAlone(0, ray));
  EXPECT_TRUE(mixed.objectBounds(0).isEmpty());
}

TEST(RayCaster, InvalidRaysMissWithoutCrashing) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster({{&box, pose(Eigen::Vector3d(0, 0, 1.0)), 1}});
  std::vector<Ray> rays(8);
  rays[0].origin.x() = kNaN;
  rays[1].direction.y() = kNaN;
  rays[2].direction = Eigen::Vector3d::Zero();
  rays[3].direction.z() = kInf;
  rays[4].t_min = kNaN;
  rays[5].t_max = kNaN;
  rays[6].t_min = 2.0;
  rays[6].t_max = 1.0;
  rays[7].origin.z() = -kInf;
  for (const Ray& ray : rays) {
    EXPECT_FALSE(caster.closestHit(ray).hit());
    EXPECT_FALSE(caster.occluded(ray));
    EXPECT_FALSE(caster.closestHitAlone(0, ray).hit());
    EXPECT_FALSE(caster.occludedAlone(0, ray));
  }
  Ray behind;  // a negative t_min counts as 0: the box is in front, nothing behind
  behind.t_min = -5.0;
  EXPECT_NEAR(caster.closestHit(behind).t, 0.98, 1e-9);
}

TEST(RayCaster, BadObjectsThrowNamingTheObject) {
  const io::TriangleMesh box = boxMesh(kHalf);
  io::TriangleMesh nan_vertex = box;
  nan_vertex.vertices[3].x() = std::numeric_limits<float>::quiet_NaN();
  io::TriangleMesh bad_index = box;
  bad_index.triangles[5][1] = 8;
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = kNaN;
  const auto message = [&](const std::vector<RenderObject>& objects) -> std::string {
    try {
      RayCaster caster(objects);
    } catch (const core::Error& e) {
      return e.what();
    }
    return "no error";
  };
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_NE(message({{&box, I, 0}, {nullptr, I, 5}}).find("object 1 (id 5)"), std::string::npos);
  EXPECT_NE(message({{&nan_vertex, I, 0}}).find("object 0"), std::string::npos);
  EXPECT_NE(message({{&bad_index, I, 0}}).find("object 0"), std::string::npos);
  EXPECT_NE(message({{&box, scaled, 0}}).find("rigid"), std::string::npos);
  EXPECT_NE(message({{&box, nan_pose, 0}}).find("non-finite"), std::string::npos);
}

TEST(RayCaster, MovedCasterKeepsItsSceneAndTheMovedFromOneHitsNothing) {
  const io::TriangleMesh box = boxMesh(kHalf);
  RayCaster first({{&box, pose(Eigen::Vector3d(0, 0, 1.0)), 3}});
  RayCaster second(std::move(first));
  Ray ray;
  EXPECT_EQ(second.closestHit(ray).object_id, 3);
  EXPECT_FALSE(first.closestHit(ray).hit());  // NOLINT(bugprone-use-after-move): documented
  EXPECT_EQ(first.objectCount(), 0);
  RayCaster third({});
  third = std::move(second);
  EXPECT_EQ(third.closestHit(ray).object_id, 3);
}

// Six boxes at different depths and tilts in front of the camera; `box` must outlive them.
std::vector<RenderObject> sixTiltedBoxes(const io::TriangleMesh& box) {
  std::vector<RenderObject> objects;
  for (int i = 0; i < 6; ++i) {
    objects.push_back({&box,
                       pose(Eigen::Vector3d(0.05 * (i - 3), 0.02 * i, 0.8 + 0.03 * i),
                            Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitX())),
                       i});
  }
  return objects;
}

TEST(RayCaster, ConcurrentQueriesAgreeWithSerialOnes) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster(sixTiltedBoxes(box));
  std::vector<Ray> rays;
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    ray.direction = Eigen::Vector3d(0.3 * std::sin(0.37 * i), 0.3 * std::cos(0.61 * i), 1.0);
    rays.push_back(ray);
  }
  std::vector<RayHit> serial;
  for (const Ray& ray : rays) serial.push_back(caster.closestHit(ray));
  std::vector<RayHit> parallel(rays.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < rays.size(); i += 4) parallel[i] = caster.closestHit(rays[i]);
    });
  }
  for (auto& thread : threads) thread.join();
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(parallel[i].object_index, serial[i].object_index);
    EXPECT_EQ(parallel[i].triangle, serial[i].triangle);
    if (serial[i].hit()) {
      ++hits;
      EXPECT_EQ(parallel[i].t, serial[i].t);
    }
  }
  EXPECT_GT(hits, 300);
}

TEST(RayCaster, BatchQueriesAgreeWithSingleOnes) {
  const io::TriangleMesh box = boxMesh(kHalf);
  const RayCaster caster(sixTiltedBoxes(box));
  std::vector<Ray> rays;
  for (int v = 0; v < 40; ++v) {
    for (int u = 0; u < 50; ++u) {
      Ray ray;
      ray.direction = Eigen::Vector3d((u - 24.7) / 80.0, (v - 19.3) / 80.0, 1.0);
      ray.t_max = 0.9;  // some rays end before the surface they point at
      rays.push_back(ray);
    }
  }
  rays[7].direction.x() = kNaN;
  rays[8].t_min = 2.0;
  const std::vector<RayHit> hits = caster.closestHits(rays);
  const std::vector<uint8_t> occluded = caster.occludedEach(rays);
  const std::vector<RayHit> alone_hits = caster.closestHitsAlone(2, rays);
  const std::vector<uint8_t> alone_occluded = caster.occludedEachAlone(2, rays);
  ASSERT_EQ(hits.size(), rays.size());
  ASSERT_EQ(occluded.size(), rays.size());
  int hit_count = 0, alone_count = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit single = caster.closestHit(rays[i]);
    ASSERT_EQ(hits[i].object_index, single.object_index) << i;
    EXPECT_EQ(hits[i].triangle, single.triangle);
    EXPECT_EQ(occluded[i] != 0, caster.occluded(rays[i]));
    if (single.hit()) {
      ++hit_count;
      EXPECT_NEAR(hits[i].t, single.t, 1e-12);
    }
    const RayHit alone = caster.closestHitAlone(2, rays[i]);
    ASSERT_EQ(alone_hits[i].object_index, alone.object_index);
    EXPECT_EQ(alone_occluded[i] != 0, caster.occludedAlone(2, rays[i]));
    alone_count += alone.hit();
  }
  EXPECT_FALSE(hits[7].hit());
  EXPECT_FALSE(hits[8].hit());
  EXPECT_GT(hit_count, 300);
  EXPECT_GT(alone_count, 50);
  EXPECT_TRUE(caster.closestHits({}).empty());
  EXPECT_THROW(caster.closestHitsAlone(6, rays), core::Error);
  EXPECT_THROW(caster.occludedEachAlone(-1, rays), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
