#include <gtest/gtest.h>

#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/simulation/depth_renderer.hpp"
#include "binpick/simulation/parts.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

PinholeCamera smallCamera() {
  PinholeCamera camera;
  camera.width = 160;
  camera.height = 120;
  camera.fx = 150.0;
  camera.fy = 170.0;
  camera.cx = 79.3;
  camera.cy = 60.7;
  return camera;
}

Eigen::Vector3d pixelRay(const PinholeCamera& camera, int u, int v) {
  return {(u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0};
}

io::TriangleMesh tiltedTriangle() {
  io::TriangleMesh mesh;
  mesh.vertices = {{-0.2f, -0.2f, 0.5f}, {0.3f, -0.1f, 0.7f}, {0.0f, 0.3f, 0.6f}};
  mesh.triangles = {{0, 1, 2}};
  return mesh;
}

std::size_t index(const PinholeCamera& camera, int u, int v) { return static_cast<std::size_t>(v) * camera.width + u; }

TEST(RenderDepth, SingleTriangleGivesExactRayPlaneDepthInsideAndInfOutside) {
  const PinholeCamera camera = smallCamera();
  const io::TriangleMesh mesh = tiltedTriangle();
  const DepthImage image = renderDepth(camera, {{&mesh, Eigen::Isometry3d::Identity(), 7}});
  ASSERT_EQ(image.width, camera.width);
  ASSERT_EQ(image.height, camera.height);
  const Eigen::Vector3d a = mesh.vertices[0].cast<double>(), b = mesh.vertices[1].cast<double>(),
                        c = mesh.vertices[2].cast<double>();
  int inside = 0, outside = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = pixelRay(camera, u, v);
      // Classify with a margin: pixel centres on an edge may go either way.
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double t = n.dot(a) / n.dot(ray);
      const Eigen::Vector3d hit = t * ray;
      const double wa = (c - b).cross(hit - b).dot(n) / n.squaredNorm();
      const double wb = (a - c).cross(hit - c).dot(n) / n.squaredNorm();
      const double wc = (b - a).cross(hit - a).dot(n) / n.squaredNorm();
      const double margin = 1e-3;
      const std::size_t i = index(camera, u, v);
      if (wa > margin && wb > margin && wc > margin) {
        ++inside;
        ASSERT_NEAR(image.depth[i], t, 1e-6 * t) << u << "," << v;
        EXPECT_EQ(image.instance[i], 7);
      } else if (wa < -margin || wb < -margin || wc < -margin) {
        ++outside;
        ASSERT_TRUE(std::isinf(image.depth[i])) << u << "," << v;
        EXPECT_EQ(image.instance[i], -1);
      }
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(RenderDepth, ObjectPoseIsApplied) {
  const PinholeCamera camera = smallCamera();
  io::TriangleMesh square;  // 2 m square at z = 0 of its own frame, facing -z
  square.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  square.triangles = {{0, 2, 1}, {0, 3, 2}};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 1.25);
  const DepthImage image = renderDepth(camera, {{&square, pose, 0}});
  for (const float z : image.depth) ASSERT_NEAR(z, 1.25f, 1e-6f);
}

TEST(RenderDepth, NearestSurfaceWinsAndTriangleFansHaveNoCracks) {
  const PinholeCamera camera = smallCamera();
  // A fan of thin triangles around a centre vertex: shared edges cross many pixel centres.
  io::TriangleMesh fan;
  fan.vertices.emplace_back(0.013f, -0.021f, 1.0f);
  const int spokes = 97;
  for (int k = 0; k < spokes; ++k) {
    const double angle = 2.0 * 3.14159265358979323846 * k / spokes;
    fan.vertices.emplace_back(static_cast<float>(3.0 * std::cos(angle)), static_cast<float>(3.0 * std::sin(angle)),
                              1.0f);
  }
  for (int k = 0; k < spokes; ++k) fan.triangles.emplace_back(0, 1 + k, 1 + (k + 1) % spokes);
  io::TriangleMesh near_triangle = tiltedTriangle();
  for (auto& v : near_triangle.vertices) v.z() *= 0.5f;  // in front of the fan
  const DepthImage image = renderDepth(
      camera, {{&fan, Eigen::Isometry3d::Identity(), 1}, {&near_triangle, Eigen::Isometry3d::Identity(), 2}});
  int near_pixels = 0;
  for (std::size_t i = 0; i < image.depth.size(); ++i) {
    ASSERT_TRUE(std::isfinite(image.depth[i])) << "crack at pixel " << i;
    if (image.instance[i] == 2) {
      ++near_pixels;
      EXPECT_LT(image.depth[i], 0.5f);
    } else {
      EXPECT_EQ(image.instance[i], 1);
      EXPECT_NEAR(image.depth[i], 1.0f, 1e-6f);
    }
  }
  EXPECT_GT(near_pixels, 100);
}

TEST(RenderDepth, TrianglesReachingBehindTheNearPlaneAreSkipped) {
  const PinholeCamera camera = smallCamera();
  io::TriangleMesh mesh;
  mesh.vertices = {{-0.5f, -0.5f, -0.2f}, {0.5f, -0.5f, 1.0f}, {0.0f, 0.5f, 1.0f}};
  mesh.triangles = {{0, 1, 2}};
  const DepthImage image = renderDepth(camera, {{&mesh, Eigen::Isometry3d::Identity(), 0}});
  for (const float z : image.depth) EXPECT_TRUE(std::isinf(z));
}

TEST(RenderDepth, RejectsMissingMesh) {
  EXPECT_THROW(renderDepth(smallCamera(), {{nullptr, Eigen::Isometry3d::Identity(), 0}}), core::Error);
}

TEST(RenderDepth, ClosedPartRendersOnlyItsFrontSurface) {
  const PinholeCamera camera = smallCamera();
  const Part part = makePart("l_bracket");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.3);
  const DepthImage image = renderDepth(camera, {{&part.mesh, pose, 3}});
  const test::PlacedMesh placed = test::place(part.mesh, pose);
  int hits = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const float z = image.depth[index(camera, u, v)];
      if (!std::isfinite(z)) continue;
      ++hits;
      // The first crossing of the pixel ray with the mesh is what a camera sees.
      const Eigen::Vector3d ray = pixelRay(camera, u, v);
      double first = std::numeric_limits<double>::infinity();
      for (const auto& t : placed.triangles) {
        const double s = test::rayTriangle(Eigen::Vector3d::Zero(), ray, placed.vertices[t[0]], placed.vertices[t[1]],
                                           placed.vertices[t[2]]);
        if (s > 0.0) first = std::min(first, s);
      }
      if (std::isfinite(first)) {
        EXPECT_NEAR(z, first, 1e-6);
      }
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(DepthToCloud, PointsProjectBackToTheirPixelWithZEqualToDepth) {
  const PinholeCamera camera = smallCamera();
  const io::TriangleMesh mesh = tiltedTriangle();
  const DepthImage image = renderDepth(camera, {{&mesh, Eigen::Isometry3d::Identity(), 0}});
  const io::PointCloud cloud = depthToCloud(camera, image);
  ASSERT_TRUE(cloud.isOrganized());
  ASSERT_EQ(cloud.width, camera.width);
  ASSERT_EQ(cloud.height, camera.height);
  int valid = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const std::size_t i = index(camera, u, v);
      const Eigen::Vector3f& p = cloud.points[i];
      if (std::isinf(image.depth[i])) {
        EXPECT_TRUE(std::isnan(p.x()) && std::isnan(p.y()) && std::isnan(p.z()));
        continue;
      }
      ++valid;
      EXPECT_EQ(p.z(), image.depth[i]);
      EXPECT_NEAR(camera.fx * p.x() / p.z() + camera.cx, u, 1e-3);
      EXPECT_NEAR(camera.fy * p.y() / p.z() + camera.cy, v, 1e-3);
    }
  }
  EXPECT_GT(valid, 1000);
}

TEST(DepthToCloud, RejectsImageOfAnotherSize) {
  DepthImage image;
  image.width = 2;
  image.height = 2;
  image.depth.assign(4, 1.0f);
  image.instance.assign(4, 0);
  EXPECT_THROW(depthToCloud(smallCamera(), image), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
