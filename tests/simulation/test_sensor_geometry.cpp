#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/simulation/depth_renderer.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/sensor_geometry.hpp"
#include "render/object_visibility.hpp"
#include "render_test_utils.hpp"
#include "thrown_message.hpp"

namespace binpick::simulation {
namespace {

using test::boxMesh;
using test::pose;

// A slab under everything, facing the camera with its top face at `depth`.
struct Floor {
  io::TriangleMesh mesh = boxMesh(Eigen::Vector3d(1.0, 1.0, 0.01));
  RenderObject at(double depth, int32_t id = -2) const {
    return {&mesh, pose(Eigen::Vector3d(0.0, 0.0, depth + 0.01)), id};
  }
};

Eigen::Isometry3d partPose() {
  return pose(Eigen::Vector3d(0.01, -0.005, 0.5), Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 1.0, 0.3).normalized()));
}

SensorGeometryParams withThreads(int threads) {
  SensorGeometryParams params;
  params.threads = threads;
  return params;
}

// Whether the segment from `a` to `b` passes through the axis-aligned box (slab test).
bool segmentMeetsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::AlignedBox3d& box) {
  double enter = 0.0, leave = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (std::abs(d) < 1e-15) {
      if (a[k] < box.min()[k] || a[k] > box.max()[k]) return false;
      continue;
    }
    double t0 = (box.min()[k] - a[k]) / d, t1 = (box.max()[k] - a[k]) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return enter <= leave;
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool sameBits(const SensorGeometry& a, const SensorGeometry& b) {
  return a.width == b.width && a.height == b.height && sameBits(a.depth, b.depth) && sameBits(a.point, b.point) &&
         sameBits(a.normal, b.normal) && sameBits(a.object_point, b.object_point) &&
         sameBits(a.object_id, b.object_id) && sameBits(a.object_index, b.object_index) &&
         sameBits(a.camera_cosine, b.camera_cosine) && sameBits(a.projector_pixel, b.projector_pixel) &&
         sameBits(a.in_projector_image, b.in_projector_image) && sameBits(a.projector_cosine, b.projector_cosine) &&
         sameBits(a.projector_distance, b.projector_distance) && sameBits(a.lit, b.lit);
}

int litPixelsOf(const SensorGeometry& g, int object_index) {
  int count = 0;
  for (std::size_t i = 0; i < g.lit.size(); ++i) {
    if (g.object_index[i] == object_index && g.lit[i]) ++count;
  }
  return count;
}

TEST(SensorGeometry, DepthAgreesWithTheRasteriserForAPinholeCamera) {
  const io::RigCalibration rig = test::simpleRig();
  const Part part = makePart("l_bracket");
  const Floor floor;
  const std::vector<RenderObject> objects{{&part.mesh, partPose(), 3}, floor.at(0.6)};
  const SensorGeometry g = computeSensorGeometry(rig, RayCaster(objects));
  PinholeCamera camera;
  camera.width = rig.camera.width;
  camera.height = rig.camera.height;
  camera.fx = rig.camera.fx;
  camera.fy = rig.camera.fy;
  camera.cx = rig.camera.cx;
  camera.cy = rig.camera.cy;
  const DepthImage image = renderDepth(camera, objects);
  int part_pixels = 0, agreeing = 0;
  const int pixels = camera.width * camera.height;
  for (int i = 0; i < pixels; ++i) {
    if (image.instance[i] == 3) ++part_pixels;
    if (image.instance[i] == g.object_id[i] && std::abs(image.depth[i] - g.depth[i]) < 1e-5) {
      ++agreeing;
    }
  }
  EXPECT_GT(part_pixels, 1000);
  // Only pixel centres grazing a silhouette may fall either way.
  EXPECT_GT(agreeing, pixels - 40);
}

TEST(SensorGeometry, WithDistortionEveryHitProjectsBackToItsPixel) {
  const io::RigCalibration rig = test::distortingRig();
  const Part part = makePart("l_bracket");
  const Floor floor;
  const SensorGeometry g = computeSensorGeometry(rig, RayCaster({{&part.mesh, partPose(), 3}, floor.at(0.6)}));
  int hits = 0;
  double worst = 0.0;
  for (int v = 0; v < g.height; ++v) {
    for (int u = 0; u < g.width; ++u) {
      const std::size_t i = g.index(u, v);
      ASSERT_GE(g.object_index[i], 0);
      ++hits;
      const Eigen::Vector2d back = rig.camera.project(g.point[i].cast<double>());
      worst = std::max(worst, (back - Eigen::Vector2d(u, v)).norm());
      EXPECT_EQ(g.depth[i], g.point[i].z());
    }
  }
  EXPECT_EQ(hits, g.width * g.height);
  EXPECT_LT(worst, 1e-3);
}

// A plate between the projector and a floor: the floor behind it, seen by the camera, is dark
// exactly where the segment to the projector centre crosses the plate.
TEST(SensorGeometry, ShadowOfAPlateMatchesTheAnalyticShadow) {
  const io::RigCalibration rig = test::simpleRig();
  const Floor floor;
  const Eigen::Vector3d plate_half(0.025, 0.025, 0.002), plate_centre(0.05, 0.0, 0.8);
  const io::TriangleMesh plate = boxMesh(plate_half);
  const SensorGeometry g = computeSensorGeometry(rig, RayCaster({floor.at(1.0, 0), {&plate, pose(plate_centre), 1}}));
  const Eigen::AlignedBox3d plate_box(plate_centre - plate_half, plate_centre + plate_half);
  const Eigen::Vector3d projector = test::projectorCentre(rig);
  const auto inShadow = [&](const Eigen::Vector3d& p) { return segmentMeetsBox(p, projector, plate_box); };
  int shadowed = 0, lit = 0, mismatches = 0;
  for (std::size_t i = 0; i < g.lit.size(); ++i) {
    if (g.object_index[i] != 0) continue;
    const Eigen::Vector3d p = g.point[i].cast<double>();
    const bool shadow = inShadow(p);
    // Away from the shadow's edge by a millimetre, the answer is unambiguous.
    bool clear_of_edge = true;
    for (const Eigen::Vector3d& step : {Eigen::Vector3d(1e-3, 0, 0), Eigen::Vector3d(0, 1e-3, 0)}) {
      clear_of_edge &= inShadow(p + step) == shadow && inShadow(p - step) == shadow;
    }
    // The camera sees more of the floor than the projector frames.
    if (!clear_of_edge || !g.in_projector_image[i]) continue;
    ASSERT_GT(g.projector_cosine[i], 0.0f);
    if (g.lit[i] == shadow) ++mismatches;
    ++(shadow ? shadowed : lit);
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(shadowed, 100);  // the camera sees the shadow
  EXPECT_GT(lit, 10000);
}

TEST(SensorGeometry, ProjectorQuantitiesAgreeWithComputingThemByHand) {
  const io::RigCalibration rig = test::distortingRig();
  const Part part = makePart("clamp");
  const Floor floor;
  const SensorGeometry g = computeSensorGeometry(rig, RayCaster({{&part.mesh, partPose(), 3}, floor.at(0.7)}));
  const Eigen::Vector3d centre = test::projectorCentre(rig);
  int inside = 0, outside = 0, lit = 0;
  for (std::size_t i = 0; i < g.lit.size(); ++i) {
    const Eigen::Vector3d p = g.point[i].cast<double>();
    const Eigen::Vector3d n = g.normal[i].cast<double>();
    const Eigen::Vector3d in_projector = rig.T_projector_camera * p;
    ASSERT_GT(in_projector.z(), 0.0);
    const Eigen::Vector2d pixel = rig.projector.project(in_projector);
    EXPECT_LT((g.projector_pixel[i].cast<double>() - pixel).norm(), 1e-3);
    EXPECT_NEAR(g.projector_distance[i], (centre - p).norm(), 1e-6);
    EXPECT_NEAR(g.projector_cosine[i], n.dot((centre - p).normalized()), 1e-5);
    EXPECT_NEAR(g.camera_cosine[i], -n.dot(p.normalized()), 1e-5);
    const double margin = 1e-3;  // pixels: a point this close to the border may go either way
    const bool clearly_inside = pixel.x() > -0.5 + margin && pixel.x() < rig.projector.width - 0.5 - margin &&
                                pixel.y() > -0.5 + margin && pixel.y() < rig.projector.height - 0.5 - margin;
    const bool clearly_outside = pixel.x() < -0.5 - margin || pixel.x() > rig.projector.width - 0.5 + margin ||
                                 pixel.y() < -0.5 - margin || pixel.y() > rig.projector.height - 0.5 + margin;
    if (clearly_inside) {
      EXPECT_TRUE(g.in_projector_image[i]);
      ++inside;
    }
    if (clearly_outside) {
      EXPECT_FALSE(g.in_projector_image[i]);
      ++outside;
    }
    if (g.lit[i]) {
      ++lit;
      EXPECT_TRUE(g.in_projector_image[i]);
      EXPECT_GT(g.projector_cosine[i], 0.0f);
    }
  }
  EXPECT_GT(inside, 10000);
  EXPECT_GT(outside, 1000);  // the projector frames less than the camera at this distance
  EXPECT_GT(lit, 10000);
}

// Far off the projector's axis a barrel lens model turns back on itself and maps points into
// the image again; they are not in its field of view and must stay dark.
TEST(SensorGeometry, PointsFoldedBackByTheProjectorDistortionAreNotLit) {
  io::RigCalibration rig;
  rig.camera = test::pinholeLens(320, 256, 80.0);  // very wide: sees far off the projector axis
  rig.projector = test::pinholeLens(320, 200, 400.0);
  rig.projector.distortion = {-0.4, 0.0, 0.0, 0.0, 0.0};
  rig.T_projector_camera = pose(Eigen::Vector3d(-0.25, 0.0, 0.0));
  const io::TriangleMesh floor = boxMesh(Eigen::Vector3d(5.0, 5.0, 0.01));
  const SensorGeometry g = computeSensorGeometry(rig, RayCaster({{&floor, pose(Eigen::Vector3d(0, 0, 1.01)), 0}}));
  int folded = 0, lit = 0;
  for (std::size_t i = 0; i < g.lit.size(); ++i) {
    const Eigen::Vector3d q = rig.T_projector_camera * g.point[i].cast<double>();
    const double radius = q.head<2>().norm() / q.z();
    const Eigen::Vector2d pixel = rig.projector.project(q);
    const bool lands_in_image = pixel.x() > 0 && pixel.x() < 319 && pixel.y() > 0 && pixel.y() < 199;
    if (radius > 1.3 && lands_in_image) {
      ++folded;
      EXPECT_FALSE(g.in_projector_image[i]);
      EXPECT_FALSE(g.lit[i]);
    }
    lit += g.lit[i];
  }
  EXPECT_GT(folded, 100);
  EXPECT_GT(lit, 1000);
}

TEST(ObjectVisibility, ALoneObjectInViewIsFullyVisible) {
  const io::RigCalibration rig = test::simpleRig();
  const io::TriangleMesh box = boxMesh(Eigen::Vector3d(0.04, 0.03, 0.02));
  const RayCaster scene(
      {{&box, pose(Eigen::Vector3d(0.02, 0.01, 0.6), Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized())),
        5}});
  const SensorGeometry g = computeSensorGeometry(rig, scene);
  const std::vector<ObjectVisibility> visibility = computeObjectVisibility(rig, scene, g);
  ASSERT_EQ(visibility.size(), 1u);
  EXPECT_GT(visibility[0].visible_lit_pixels, 1000);
  EXPECT_EQ(visibility[0].alone_lit_pixels, visibility[0].visible_lit_pixels);
  EXPECT_EQ(visibility[0].visible_fraction, 1.0);
}

TEST(ObjectVisibility, APlateCoveringHalfAnObjectHalvesItsFraction) {
  const io::RigCalibration rig = test::simpleRig();
  const io::TriangleMesh box = boxMesh(Eigen::Vector3d(0.05, 0.05, 0.01));
  const io::TriangleMesh plate = boxMesh(Eigen::Vector3d(0.1, 0.2, 0.002));
  const Floor floor;
  // The plate covers every camera ray with x < 0, so the left half of the box; its projector
  // shadow falls further left, clear of the box.
  const RayCaster scene({{&box, pose(Eigen::Vector3d(0.0, 0.0, 0.6)), 0},
                         {&plate, pose(Eigen::Vector3d(-0.1, 0.0, 0.4)), 1},
                         floor.at(0.8)});
  const SensorGeometry g = computeSensorGeometry(rig, scene);
  const std::vector<ObjectVisibility> visibility = computeObjectVisibility(rig, scene, g);
  ASSERT_EQ(visibility.size(), 3u);
  const ObjectVisibility& half = visibility[0];
  EXPECT_GT(half.alone_lit_pixels, 1000);
  EXPECT_NEAR(half.visible_fraction, 0.5, 0.05);
  EXPECT_EQ(half.visible_fraction, static_cast<double>(half.visible_lit_pixels) / half.alone_lit_pixels);
  EXPECT_EQ(visibility[1].visible_fraction, 1.0);  // nothing covers or shadows the plate
  EXPECT_LT(visibility[2].visible_fraction, 0.9);  // the floor loses to both

  // A chosen subset, in the order asked for.
  const std::vector<ObjectVisibility> subset = computeObjectVisibilityOf(rig, scene, g, {2, 0, 2});
  ASSERT_EQ(subset.size(), 3u);
  EXPECT_EQ(subset[0].alone_lit_pixels, visibility[2].alone_lit_pixels);
  EXPECT_EQ(subset[1].visible_lit_pixels, visibility[0].visible_lit_pixels);
  EXPECT_EQ(subset[1].visible_fraction, visibility[0].visible_fraction);
  EXPECT_EQ(subset[2].alone_lit_pixels, visibility[2].alone_lit_pixels);
  EXPECT_THROW(computeObjectVisibilityOf(rig, scene, g, {3}), core::Error);
}

// A heap of parts seen through distorting lenses: each object's alone count equals the lit pixels
// of a scene holding just that object, which checks that the bounding-box search misses nothing.
TEST(ObjectVisibility, AloneCountsMatchRenderingEachObjectAloneInAHeap) {
  const io::RigCalibration rig = test::distortingRig();
  const Part part = makePart("l_bracket");
  const Floor floor;
  std::vector<RenderObject> objects;
  for (int i = 0; i < 8; ++i) {
    // Overlapping in the camera's view, some near the image border where distortion is largest.
    const Eigen::Vector3d position(0.09 * std::cos(1.9 * i), 0.07 * std::sin(2.3 * i), 0.55 + 0.012 * i);
    const Eigen::Vector3d axis(std::sin(0.7 * i), std::cos(1.3 * i), 0.5);
    objects.push_back(
        {&part.mesh, pose(position, Eigen::AngleAxisd(0.9 * i, axis.normalized())), static_cast<int32_t>(i)});
  }
  objects.push_back({&part.mesh, pose(Eigen::Vector3d(0.21, 0.16, 0.6)), 8});  // a corner
  objects.push_back(floor.at(0.66));
  const RayCaster scene(objects);
  const SensorGeometry one = computeSensorGeometry(rig, scene, withThreads(1));
  const SensorGeometry two = computeSensorGeometry(rig, scene, withThreads(2));
  EXPECT_TRUE(sameBits(one, two));
  const std::vector<ObjectVisibility> visibility = computeObjectVisibility(rig, scene, one, withThreads(1));
  const std::vector<ObjectVisibility> again = computeObjectVisibility(rig, scene, one, withThreads(2));
  ASSERT_EQ(visibility.size(), objects.size());
  int partly_hidden = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    EXPECT_EQ(visibility[i].alone_lit_pixels, again[i].alone_lit_pixels);
    EXPECT_EQ(visibility[i].visible_lit_pixels, litPixelsOf(one, static_cast<int>(i)));
    EXPECT_LE(visibility[i].visible_lit_pixels, visibility[i].alone_lit_pixels);
    const SensorGeometry alone = computeSensorGeometry(rig, RayCaster({objects[i]}));
    EXPECT_EQ(visibility[i].alone_lit_pixels, litPixelsOf(alone, 0)) << "object " << i;
    EXPECT_GT(visibility[i].alone_lit_pixels, 0) << "object " << i;
    if (visibility[i].visible_fraction < 0.99) ++partly_hidden;
  }
  EXPECT_GT(partly_hidden, 2);
}

// Sub-pixel samples through the pixel centres see what the image's own rays see.
TEST(SensorGeometry, SamplesAtPixelCentresSeeWhatThePixelsSee) {
  const io::RigCalibration rig = test::distortingRig();
  const Part part = makePart("l_bracket");
  const Floor floor;
  const RayCaster scene({{&part.mesh, partPose(), 3}, floor.at(0.6)});
  const SensorGeometry image = computeSensorGeometry(rig, scene);
  std::vector<Eigen::Vector2d> centres;
  for (int v = 0; v < rig.camera.height; v += 3) {
    for (int u = 0; u < rig.camera.width; ++u) centres.emplace_back(u, v);
  }
  const SensorGeometry samples = computeSensorGeometryAt(rig, scene, centres, rig.camera.width);
  ASSERT_EQ(samples.width, rig.camera.width);
  ASSERT_EQ(samples.height, (rig.camera.height + 2) / 3);
  int on_part = 0;
  for (int row = 0; row < samples.height; ++row) {
    for (int u = 0; u < samples.width; ++u) {
      const std::size_t s = samples.index(u, row), i = image.index(u, 3 * row);
      ASSERT_EQ(samples.object_id[s], image.object_id[i]) << u << ", " << 3 * row;
      if (image.object_id[i] < 0) continue;
      EXPECT_NEAR(samples.depth[s], image.depth[i], 1e-6f);
      EXPECT_EQ(samples.lit[s], image.lit[i]) << u << ", " << 3 * row;
      on_part += image.object_id[i] == 3;
    }
  }
  EXPECT_GT(on_part, 100);
  EXPECT_NE(binpick::test::thrownMessage([&] { computeSensorGeometryAt(rig, scene, centres, 7); })
                .find("do not make rows of 7"),
            std::string::npos);
}

TEST(SensorGeometry, EmptySceneGivesEmptyBuffers) {
  const io::RigCalibration rig = test::distortingRig();
  const RayCaster scene({});
  const SensorGeometry g = computeSensorGeometry(rig, scene);
  ASSERT_EQ(g.depth.size(), static_cast<std::size_t>(rig.camera.width * rig.camera.height));
  for (std::size_t i = 0; i < g.depth.size(); ++i) {
    ASSERT_TRUE(std::isnan(g.depth[i]));
    ASSERT_TRUE(g.point[i].array().isNaN().all());
    ASSERT_TRUE(std::isnan(g.projector_pixel[i].x()));
    ASSERT_EQ(g.object_id[i], -1);
    ASSERT_EQ(g.object_index[i], -1);
    ASSERT_EQ(g.lit[i], 0);
    ASSERT_EQ(g.in_projector_image[i], 0);
  }
  EXPECT_TRUE(computeObjectVisibility(rig, scene, g).empty());
}

TEST(SensorGeometry, BadParamsRigsAndGeometriesThrowNamingTheProblem) {
  const io::RigCalibration rig = test::simpleRig();
  const RayCaster scene({});
  const auto message = [&](const io::RigCalibration& r, const SensorGeometryParams& p) -> std::string {
    try {
      computeSensorGeometry(r, scene, p);
    } catch (const core::Error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(rig, withThreads(-1)).find("threads"), std::string::npos);
  SensorGeometryParams nan_offset;
  nan_offset.shadow_ray_offset = std::nan("");
  EXPECT_NE(message(rig, nan_offset).find("shadow_ray_offset"), std::string::npos);
  io::RigCalibration bad_rig = rig;
  bad_rig.projector.fx = 0.0;
  EXPECT_NE(message(bad_rig, {}).find("projector"), std::string::npos);

  SensorGeometry wrong_size = computeSensorGeometry(rig, scene);
  wrong_size.lit.pop_back();
  EXPECT_THROW(computeObjectVisibility(rig, scene, wrong_size), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
