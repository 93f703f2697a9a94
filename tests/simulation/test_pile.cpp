#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "binpick/core/error.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"
#include "mesh_test_utils.hpp"

namespace binpick::simulation {
namespace {

// A quarter-resolution camera keeps the tests fast; the geometry of the pile does not change.
PileParams smallPile(uint64_t seed, int objects = 20) {
  PileParams params;
  params.objects = objects;
  params.seed = seed;
  params.rig.camera = params.rig.camera.scaled(0.5);
  return params;
}

Eigen::Isometry3d binPose(const PileScene& scene, const ObjectTruth& truth) {
  return scene.T_camera_bin.inverse() * truth.T_camera_object;
}

bool sameBits(const io::PointCloud& a, const io::PointCloud& b) {
  return a.points.size() == b.points.size() &&
         std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(Eigen::Vector3f)) == 0;
}

TEST(Pile, SameSeedGivesBitIdenticalSceneAndOtherSeedsDiffer) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  PileParams params = smallPile(42, 12);
  params.dropout = 0.05;
  const PileScene first = generatePile(part, params);
  const PileScene again = generatePile(part, params);
  EXPECT_TRUE(sameBits(first.cloud, again.cloud));
  EXPECT_EQ(first.instance, again.instance);
  ASSERT_EQ(first.objects.size(), again.objects.size());
  for (std::size_t i = 0; i < first.objects.size(); ++i) {
    EXPECT_TRUE(first.objects[i].T_camera_object.matrix() == again.objects[i].T_camera_object.matrix());
    EXPECT_EQ(first.objects[i].visible_pixels, again.objects[i].visible_pixels);
  }
  params.seed = 43;
  const PileScene other = generatePile(part, params);
  EXPECT_FALSE(sameBits(first.cloud, other.cloud));
  EXPECT_FALSE(first.objects[0].T_camera_object.isApprox(other.objects[0].T_camera_object, 1e-6));
}

TEST(Pile, OutputShapesAndCameraConvention) {
  const PileParams params = smallPile(3, 5);
  const PileScene scene = generatePile(makePart("clamp").mesh, params);
  EXPECT_EQ(scene.cloud.width, params.rig.camera.width);
  EXPECT_EQ(scene.cloud.height, params.rig.camera.height);
  EXPECT_TRUE(scene.cloud.isOrganized());
  EXPECT_EQ(scene.instance.size(), scene.cloud.size());
  EXPECT_EQ(scene.objects.size(), 5u);
  // Floor centre straight ahead at camera_height; the bin's z (up) points back at the camera.
  EXPECT_TRUE(scene.T_camera_bin.translation().isApprox(Eigen::Vector3d(0, 0, params.camera_height)));
  EXPECT_TRUE((scene.T_camera_bin.linear() * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(scene.T_camera_bin.linear().determinant(), 1.0, 1e-12);
  // The centre pixel sees the floor (or a part) about camera_height away; outside the bin nothing.
  const std::size_t centre =
      static_cast<std::size_t>(params.rig.camera.height / 2) * params.rig.camera.width + params.rig.camera.width / 2;
  EXPECT_LE(scene.cloud.points[centre].z(), params.camera_height + 0.005);
  EXPECT_EQ(scene.instance[0], -1);
  EXPECT_TRUE(std::isnan(scene.cloud.points[0].z()));
  const int bin_pixels = static_cast<int>(std::count(scene.instance.begin(), scene.instance.end(), -2));
  EXPECT_GT(bin_pixels, 10000);
}

TEST(Pile, PartsLieInsideTheBinAndTheFirstRestsOnTheFloor) {
  for (const auto& name : partNames()) {
    SCOPED_TRACE(name);
    const io::TriangleMesh part = makePart(name).mesh;
    const PileParams params = smallPile(7);
    const PileScene scene = generatePile(part, params);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const auto placed = test::place(part, binPose(scene, scene.objects[i]));
      EXPECT_GE(placed.box.min().x(), -0.5 * params.bin_length - 1e-3) << "part " << i;
      EXPECT_LE(placed.box.max().x(), 0.5 * params.bin_length + 1e-3) << "part " << i;
      EXPECT_GE(placed.box.min().y(), -0.5 * params.bin_width - 1e-3) << "part " << i;
      EXPECT_LE(placed.box.max().y(), 0.5 * params.bin_width + 1e-3) << "part " << i;
      EXPECT_GE(placed.box.min().z(), -1e-3) << "part " << i;
    }
    // Something rests on the floor: the collision shapes' margins keep it within a millimetre.
    double lowest = 1.0;
    for (const auto& object : scene.objects)
      lowest = std::min(lowest, test::place(part, binPose(scene, object)).box.min().z());
    EXPECT_NEAR(lowest, 0.0, 1.5e-3);
  }
}

TEST(Pile, PartsDoNotInterpenetrate) {
  // A flat, a toothed and a turned part: the three kinds of collision shape.
  for (const std::string name : {"l_bracket", "gear", "ring_magnet"}) {
    SCOPED_TRACE(name);
    const io::TriangleMesh part = makePart(name).mesh;
    // A small bin makes a tall pile with many contacts.
    PileParams params = smallPile(11, 16);
    params.bin_length = 0.20;
    params.bin_width = 0.16;
    const PileScene scene = generatePile(part, params);
    std::vector<test::PlacedMesh> placed;
    for (const auto& object : scene.objects) placed.push_back(test::place(part, binPose(scene, object)));
    int touching_pairs = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      for (std::size_t j = 0; j < placed.size(); ++j) {
        if (i == j || !placed[i].box.intersects(placed[j].box)) continue;
        ++touching_pairs;
        EXPECT_LT(test::penetrationDepth(placed[i], placed[j]), 1e-3) << "part " << i << " into part " << j;
      }
    }
    EXPECT_GT(touching_pairs, 10);  // the check only means something if parts are close
  }
}

// The interpenetration check itself must be able to fail.
TEST(Pile, PenetrationCheckDetectsOverlappingParts) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  Eigen::Isometry3d shifted = Eigen::Isometry3d::Identity();
  shifted.translation() = Eigen::Vector3d(0.004, 0.003, 0.005);
  const auto a = test::place(part, Eigen::Isometry3d::Identity());
  const auto b = test::place(part, shifted);
  EXPECT_GT(test::penetrationDepth(a, b), 2e-3);
}

TEST(Pile, VisibleFractionsAreConsistent) {
  const PileScene scene = generatePile(makePart("l_bracket").mesh, smallPile(5, 20));
  int labelled = 0;
  double best = 0.0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectTruth& truth = scene.objects[i];
    EXPECT_GE(truth.visible_fraction, 0.0);
    EXPECT_LE(truth.visible_fraction, 1.0);
    EXPECT_LE(truth.visible_pixels, truth.unoccluded_pixels);
    EXPECT_GT(truth.unoccluded_pixels, 0);
    const int count = static_cast<int>(std::count(scene.instance.begin(), scene.instance.end(), int32_t(i)));
    // Visible pixels are those the camera sees lit: a subset of the pixels labelled with it.
    EXPECT_LE(truth.visible_pixels, count);
    EXPECT_GE(truth.visible_pixels, count / 2);
    labelled += count;
    best = std::max(best, truth.visible_fraction);
  }
  EXPECT_GT(labelled, 0);
  EXPECT_GT(best, 0.9);  // some part lies on top, fully seen and lit
}

TEST(Pile, SinglePartIsFullyVisible) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const PileScene scene = generatePile(makePart("clamp").mesh, smallPile(seed, 1));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_NEAR(scene.objects[0].visible_fraction, 1.0, 0.01);
  }
}

TEST(Pile, NoiseFreePixelsLieOnTheLabelledSurface) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  PileParams params = smallPile(9, 10);
  params.depth_noise = 0.0;
  const PileScene scene = generatePile(part, params);
  std::vector<test::PlacedMesh> in_camera;
  for (const auto& object : scene.objects) in_camera.push_back(test::place(part, object.T_camera_object));
  int checked = 0;
  for (std::size_t i = 0; i < scene.instance.size(); i += 97) {
    const int32_t id = scene.instance[i];
    if (id < 0) continue;
    EXPECT_LT(test::distanceToSurface(in_camera[id], scene.exact_cloud.points[i].cast<double>()), 1e-5);
    // The measured cloud holds the lit ones among them, at the same place.
    if (scene.cloud.points[i].allFinite()) {
      EXPECT_EQ(scene.cloud.points[i], scene.exact_cloud.points[i]);
    }
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(Pile, DepthNoiseMovesPointsAlongTheirRays) {
  const io::TriangleMesh part = makePart("l_bracket").mesh;
  PileParams params = smallPile(4, 5);
  params.depth_noise = 0.0;
  const PileScene clean = generatePile(part, params);
  params.depth_noise = 0.002;
  const PileScene noisy = generatePile(part, params);
  double sum = 0.0, sum_squares = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < clean.cloud.size(); ++i) {
    const Eigen::Vector3d p = clean.cloud.points[i].cast<double>(), q = noisy.cloud.points[i].cast<double>();
    ASSERT_EQ(std::isnan(p.z()), std::isnan(q.z()));
    if (std::isnan(p.z())) continue;
    EXPECT_LT(p.normalized().cross(q.normalized()).norm(), 1e-6);
    const double along = q.norm() - p.norm();
    sum += along;
    sum_squares += along * along;
    ++n;
  }
  ASSERT_GT(n, 10000);
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 1e-4);
  EXPECT_NEAR(std::sqrt(sum_squares / n - mean * mean), 0.002, 1e-4);
}

TEST(Pile, DropoutRemovesTheRequestedShareOfPixels) {
  const io::TriangleMesh part = makePart("clamp").mesh;
  PileParams params = smallPile(8, 5);
  const PileScene full = generatePile(part, params);
  params.dropout = 0.3;
  const PileScene dropped = generatePile(part, params);
  int valid = 0, lost = 0;
  for (std::size_t i = 0; i < full.cloud.size(); ++i) {
    if (std::isnan(full.cloud.points[i].z())) continue;
    ++valid;
    if (std::isnan(dropped.cloud.points[i].z())) ++lost;
  }
  EXPECT_NEAR(static_cast<double>(lost) / valid, 0.3, 0.01);
}

TEST(Pile, EmptyBinIsAValue) {
  const PileScene scene = generatePile(makePart("clamp").mesh, smallPile(1, 0));
  EXPECT_TRUE(scene.objects.empty());
  EXPECT_EQ(std::count(scene.instance.begin(), scene.instance.end(), 0), 0);
}

TEST(PileParams, ValidateNamesTheBadField) {
  const auto message = [](PileParams params) {
    try {
      params.validate();
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  PileParams params;
  EXPECT_NO_THROW(params.validate());
  params.bin_length = -0.4;
  EXPECT_NE(message(params).find("bin_length"), std::string::npos);
  params = PileParams{};
  params.dropout = 1.5;
  EXPECT_NE(message(params).find("dropout"), std::string::npos);
  params = PileParams{};
  params.camera_height = 0.1;
  EXPECT_NE(message(params).find("camera_height"), std::string::npos);
  params = PileParams{};
  params.rig.camera.fx = 0.0;
  EXPECT_NE(message(params).find("camera.fx"), std::string::npos);
  params = PileParams{};
  params.objects = -1;
  EXPECT_NE(message(params).find("objects"), std::string::npos);
}

TEST(Pile, RejectsAPartThatCannotFitInTheBin) {
  PileParams params = smallPile(1, 1);
  params.bin_length = 0.05;
  params.bin_width = 0.05;
  EXPECT_THROW(generatePile(makePart("l_bracket").mesh, params), core::Error);
}

}  // namespace
}  // namespace binpick::simulation
